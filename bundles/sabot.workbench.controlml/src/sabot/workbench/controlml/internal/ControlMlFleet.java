package sabot.workbench.controlml.internal;

import java.time.Clock;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.atomic.AtomicInteger;

import org.eclipse.core.runtime.preferences.IEclipsePreferences;
import org.eclipse.core.runtime.preferences.IEclipsePreferences.IPreferenceChangeListener;
import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.Deactivate;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.GridMap;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.controlml.payload.NoQuery;
import sabot.controlml.payload.VelocityCommand;
import sabot.fleet.ArchivedCommand;
import sabot.fleet.ServerFigures;
import sabot.identity.DeviceIdentityManager;
import sabot.model.geometry.Twist2D;
import sabot.workbench.account.XmppAccountStore;
import sabot.workbench.fleet.ConnectionStatus;
import sabot.workbench.fleet.FleetCommandException;
import sabot.workbench.fleet.FleetListener;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.QueuedCommand;
import sabot.workbench.fleet.RobotIdentity;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.fleet.TrafficStatistics;

/**
 * The faceless ControlML plug-in: the workbench's one XMPP connection (the account of the preferences), the robots of
 * its roster, their presence levels and telemetry, published as {@link FleetState}. Put together from
 * {@link FleetConnection} (connection and back-off), {@link FleetRoster} (roster and lobby), {@link FleetTelemetry},
 * {@link FleetRequests} and {@link RobotMaps}, around the {@link RobotRegistry} they all update.
 * <p>
 * Threads: one connection thread (connect, log in, follow robots, back-off), a small pool for requests (each waits
 * for its robot's answer), and one notification thread that calls the listeners in order. Smack's threads only
 * update the state and queue notifications. All of them run at {@link #BACKGROUND_PRIORITY}.
 */
@Component(service = FleetState.class, immediate = true)
public final class ControlMlFleet implements FleetState {

    /** Roster group of the robots the workbench follows (fleet rule 12 puts configured robots there). */
    public static final String ROBOTS_GROUP = "Sabot robots";

    /**
     * Priority of every thread of the connection, its own and Smack's: below the UI thread's, so that a frame need not
     * wait for telemetry ingest on a busy core. Linux applies it as the nice value the product's start script sets
     * (SABOT_WORKBENCH_BACKGROUND_NICE, default 10, docs/WORKBENCH.md); without the script's JVM options (0, or the
     * UI tests' runtime) HotSpot only records Java priorities. An ingest that falls behind shows: late poses grey
     * their robot (RobotState.isLate).
     */
    static final int BACKGROUND_PRIORITY = Thread.MIN_PRIORITY;

    private static final Logger LOG = LoggerFactory.getLogger("sabot.workbench.controlml");

    private final Clock clock;
    private final ExecutorService requestPool = Executors.newFixedThreadPool(4, named("sabot-fleet-request"));
    /** Sends stored commands for offline robots: a send waits for no answer, so never behind the pool's requests. */
    private final ExecutorService storedCommands = Executors.newSingleThreadExecutor(named("sabot-fleet-stored"));
    private final ExecutorService notifier = Executors.newSingleThreadExecutor(named("sabot-fleet-events"));
    private final RobotRegistry registry;
    private final FleetRequests requests;
    private final FleetTelemetry telemetry;
    private final RobotMaps maps;
    private final FleetTraffic traffic;
    private final FleetWatch watch;
    private final FleetConnection connection;
    private final IPreferenceChangeListener accountChanged = e -> {
        if (e.getKey().startsWith(XmppAccountStore.KEY_PREFIX)) {
            reconnect();
        }
    };
    private IEclipsePreferences node;

    public ControlMlFleet() {
        this(Clock.systemUTC(), new Backoff(Duration.ofMillis(500), Duration.ofSeconds(30)), Duration.ofSeconds(10));
    }

    ControlMlFleet(Clock clock, Backoff backoff, Duration requestTimeout) {
        this.clock = clock;
        ScheduledExecutorService connector = Executors.newSingleThreadScheduledExecutor(named(
                "sabot-fleet-connection"));
        registry = new RobotRegistry(clock, notifier);
        traffic = new FleetTraffic(System::nanoTime, jid -> registry.robot(jid) != null);
        requests = new FleetRequests(requestPool, storedCommands, this::session, registry, traffic);
        watch = new FleetWatch(this::session);
        telemetry = new FleetTelemetry(clock, registry, requests, traffic, watch, connector, this::session);
        FleetRoster roster = new FleetRoster(registry, telemetry, connector, this::session);
        maps = new RobotMaps(this);
        connection = new FleetConnection(connector, named("sabot-fleet-liveness"), backoff, requestTimeout, registry,
                roster, telemetry, maps, requests, traffic);
    }

    private FleetSession session() {
        return connection.session();
    }

    @Activate
    void activate() {
        // vcard-temp parsed with the device fields (GEO, FN, ROLE) that Smack's own provider drops
        DeviceIdentityManager.registerProvider();
        node = XmppAccountStore.workbenchNode();
        node.addPreferenceChangeListener(accountChanged);
        connection.start();
        LOG.info("ControlML plug-in started");
    }

    @Deactivate
    void deactivate() {
        if (node != null) {
            node.removePreferenceChangeListener(accountChanged);
        }
        connection.stop();
        watch.sessionClosed();
        requestPool.shutdownNow();
        storedCommands.shutdownNow();
        notifier.shutdown();
        LOG.info("ControlML plug-in stopped");
    }

    @Override
    public void watch(String viewer, Map<String, Double> rates) {
        watch.watch(viewer, rates);
    }

    @Override
    public ConnectionStatus connection() {
        return registry.status();
    }

    @Override
    public List<RobotState> robots() {
        return registry.robots();
    }

    @Override
    public Optional<RobotState> robot(String jid) {
        return Optional.ofNullable(registry.robot(jid));
    }

    @Override
    public List<String> accessRequests() {
        return registry.accessRequests();
    }

    @Override
    public void addListener(FleetListener listener) {
        registry.addListener(listener);
    }

    @Override
    public void removeListener(FleetListener listener) {
        registry.removeListener(listener);
    }

    @Override
    public void reconnect() {
        connection.reconnect();
    }

    @Override
    public CompletableFuture<Void> goTo(String robot, Goal goal) {
        return withPlan(robot, this.<Goal>set(robot, Resources.GOAL, goal));
    }

    /** {@inheritDoc} The plan of the first leg is fetched once the robot took it, the others as it starts them. */
    @Override
    public CompletableFuture<Void> startMission(String robot, List<MissionTarget> targets, boolean queue) {
        MissionStatus command;
        try {
            command = missionCommand(registry.robot(robot), targets, queue);
        } catch (IllegalArgumentException e) {
            return CompletableFuture.failedFuture(new FleetCommandException(ControlMlCondition.INVALID_VALUE, e
                    .getMessage()));
        }
        return withPlan(robot, set(robot, Resources.MISSION, command));
    }

    /**
     * @param robot   the robot as last known (its maintenance flag is sent back, so that the robot reads no mode
     *                switch), or null
     * @param targets 1..{@link MissionStatus#MAX_TARGETS}
     * @return the {@code cm.mission} set that starts ({@code running}) or queues ({@code queued}) a mission of
     *         {@code targets}, each pending
     * @throws IllegalArgumentException for no target (a set of {@code running} without targets would be a resume)
     *                                  or too many
     */
    static MissionStatus missionCommand(RobotState robot, List<MissionTarget> targets, boolean queue) {
        if (targets.isEmpty()) {
            throw new IllegalArgumentException("a mission needs at least one target");
        }
        boolean maintenance = robot != null && robot.mission() != null && robot.mission().maintenance();
        List<MissionTarget> pending = targets.stream().map(t -> t.in(MissionTarget.State.PENDING)).toList();
        return new MissionStatus(queue ? MissionState.QUEUED : MissionState.RUNNING, maintenance, 0, "", pending, 0,
                0);
    }

    /** @return {@code taken}'s answer alone; once the robot took the command, its plan is fetched to show it */
    private CompletableFuture<Void> withPlan(String robot, CompletableFuture<?> taken) {
        CompletableFuture<Void> sent = taken.thenApply(readBack -> null);
        sent.thenRun(() -> telemetry.fetchPlan(robot));
        return sent;
    }

    @Override
    public CompletableFuture<Void> goToWhenOnline(String robot, Goal goal) {
        return requests.goToWhenOnline(robot, goal);
    }

    @Override
    public List<QueuedCommand> queuedCommands() {
        return registry.queuedCommands();
    }

    @Override
    public CompletableFuture<Void> stop(String robot) {
        RobotState r = registry.robot(robot);
        MissionStatus m = r == null ? null : r.mission();
        if (m != null && m.state().isActive()) {
            // the robot's own maintenance flag, so that the command is read as a transition, not a mode switch
            return set(robot, Resources.MISSION, new MissionStatus(MissionState.ABORTED, m.maintenance(), m.progress(),
                    "stopped by the operator")).thenApply(x -> null);
        }
        return drive(robot, Twist2D.ZERO);
    }

    @Override
    public CompletableFuture<Void> drive(String robot, Twist2D twist) {
        return set(robot, Resources.VELOCITY, new VelocityCommand(clock.instant(), twist)).thenApply(x -> null);
    }

    /** {@inheritDoc} From the robot's remote files when {@code cm.map} cannot carry it ({@link RobotMaps}). */
    @Override
    public CompletableFuture<GridMap> map(String robot) {
        return maps.map(robot);
    }

    @Override
    public <T> CompletableFuture<T> get(String robot, Resource<T, NoQuery> resource) {
        return requests.get(robot, resource);
    }

    @Override
    public <T, Q> CompletableFuture<T> get(String robot, Resource<T, Q> resource, Q query) {
        return requests.get(robot, resource, query);
    }

    @Override
    public <T> CompletableFuture<T> set(String robot, Resource<T, ?> resource, T value) {
        return requests.set(robot, resource, value);
    }

    /**
     * The robot's vCard (vcard-temp, stored by the server, so it is read while the robot is offline too), parsed with
     * {@code sabot.identity}'s device profile, on the request pool.
     */
    @Override
    public CompletableFuture<RobotIdentity> identity(String robot) {
        return requests.identity(robot);
    }

    /** {@inheritDoc} Counted by {@link FleetTraffic} on the session's threads; computed here. */
    @Override
    public Optional<TrafficStatistics> traffic(String robot) {
        return traffic.snapshot(robot);
    }

    @Override
    public CompletableFuture<ServerFigures> serverStatistics(String robot, java.time.Duration window) {
        return requests.serverStatistics(robot, window);
    }

    @Override
    public CompletableFuture<List<ArchivedCommand>> commandHistory(String robot, int max) {
        return requests.commandHistory(robot, max);
    }

    /**
     * The fleet's threads, at {@link #BACKGROUND_PRIORITY}. Smack's reader, writer and executor threads are started
     * from them and inherit it.
     */
    private static ThreadFactory named(String name) {
        AtomicInteger n = new AtomicInteger();
        return r -> {
            Thread t = new Thread(r, name + "-" + n.incrementAndGet());
            t.setDaemon(true);
            t.setPriority(BACKGROUND_PRIORITY);
            return t;
        };
    }
}
