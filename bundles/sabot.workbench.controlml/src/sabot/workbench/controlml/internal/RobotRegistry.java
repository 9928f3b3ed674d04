package sabot.workbench.controlml.internal;

import java.time.Clock;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.ConcurrentSkipListMap;
import java.util.concurrent.CopyOnWriteArraySet;
import java.util.concurrent.ExecutorService;
import java.util.function.UnaryOperator;

import sabot.workbench.fleet.ConnectionStatus;
import sabot.workbench.fleet.ConnectionStatus.State;
import sabot.workbench.fleet.FleetListener;
import sabot.workbench.fleet.QueuedCommand;
import sabot.workbench.fleet.RobotState;

/**
 * What the fleet knows: the robots followed (by bare JID, sorted) with their latest state, and the connection's
 * status; every change told to the listeners in order on one notification thread. Only the roster adds and removes
 * robots; presence and telemetry update those it holds.
 */
final class RobotRegistry {

    private final Clock clock;
    private final ExecutorService notifier;
    private final Map<String, RobotState> robots = new ConcurrentSkipListMap<>();
    private final Set<FleetListener> listeners = new CopyOnWriteArraySet<>();
    private final Object stateLock = new Object();
    private volatile ConnectionStatus status;
    /** The commands waiting for offline robots, oldest first (FleetState.queuedCommands). */
    private volatile List<QueuedCommand> queued = List.of();
    /** The robots asking for access, sorted (FleetState.accessRequests). */
    private volatile List<String> asking = List.of();

    RobotRegistry(Clock clock, ExecutorService notifier) {
        this.clock = clock;
        this.notifier = notifier;
        this.status = new ConnectionStatus(State.CONNECTING, "", "", clock.instant());
    }

    ConnectionStatus status() {
        return status;
    }

    List<RobotState> robots() {
        return List.copyOf(robots.values());
    }

    /** @return the robot's state, or null when it is not followed */
    RobotState robot(String jid) {
        return robots.get(jid);
    }

    /** @return the JIDs followed, a copy */
    List<String> jids() {
        return List.copyOf(robots.keySet());
    }

    void addListener(FleetListener listener) {
        // queued on the notification thread: the listener sees the present state first, then every later change
        notifier.execute(() -> {
            if (listeners.add(listener)) {
                listener.connectionChanged(status);
                robots.values().forEach(listener::robotChanged);
                listener.accessRequestsChanged(asking);
                listener.queuedCommandsChanged(queued);
            }
        });
    }

    void removeListener(FleetListener listener) {
        listeners.remove(listener);
    }

    /** Changes a robot followed; nothing for one that is not (telemetry or presence of someone else). */
    void update(String jid, UnaryOperator<RobotState> change) {
        synchronized (stateLock) {
            RobotState before = robots.get(jid);
            if (before == null) {
                return;
            }
            RobotState after = change.apply(before);
            robots.put(jid, after);
            notifier.execute(() -> listeners.forEach(l -> l.robotChanged(after)));
        }
    }

    /** Follows a robot from now on, its state unknown (the roster's). */
    void add(String jid, String name) {
        synchronized (stateLock) {
            if (!robots.containsKey(jid)) {
                RobotState r = RobotState.unknown(jid, name);
                robots.put(jid, r);
                notifier.execute(() -> listeners.forEach(l -> l.robotChanged(r)));
            }
        }
    }

    void remove(String jid) {
        synchronized (stateLock) {
            if (robots.remove(jid) != null) {
                notifier.execute(() -> listeners.forEach(l -> l.robotRemoved(jid)));
            }
        }
    }

    /** @return the commands waiting for offline robots, oldest first */
    List<QueuedCommand> queuedCommands() {
        return queued;
    }

    /** A command now waits for an offline robot; listeners hear of it. */
    void addQueued(QueuedCommand command) {
        synchronized (stateLock) {
            List<QueuedCommand> now = new java.util.ArrayList<>(queued);
            now.add(command);
            setQueued(List.copyOf(now));
        }
    }

    /** The command with this id no longer waits (answered); nothing when none does. */
    void removeQueued(String id) {
        synchronized (stateLock) {
            List<QueuedCommand> now = queued.stream().filter(q -> !q.id().equals(id)).toList();
            if (now.size() != queued.size()) {
                setQueued(now);
            }
        }
    }

    private void setQueued(List<QueuedCommand> now) {
        queued = now;
        notifier.execute(() -> listeners.forEach(l -> l.queuedCommandsChanged(now)));
    }

    /** @return the robots asking for access, sorted */
    List<String> accessRequests() {
        return asking;
    }

    /** @return whether {@code jid} asks for access */
    boolean asking(String jid) {
        return asking.contains(jid);
    }

    /** The robots asking for access now (any order); listeners hear of a change. */
    void setAccessRequests(java.util.Collection<String> jids) {
        synchronized (stateLock) {
            List<String> now = jids.stream().sorted().distinct().toList();
            if (!now.equals(asking)) {
                asking = now;
                notifier.execute(() -> listeners.forEach(l -> l.accessRequestsChanged(now)));
            }
        }
    }

    void setStatus(State state, String account, String detail) {
        synchronized (stateLock) {
            ConnectionStatus s = new ConnectionStatus(state, account, detail, clock.instant());
            status = s;
            notifier.execute(() -> listeners.forEach(l -> l.connectionChanged(s)));
        }
    }
}
