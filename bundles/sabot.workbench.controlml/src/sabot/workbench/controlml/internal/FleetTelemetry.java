package sabot.workbench.controlml.internal;

import java.time.Clock;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;
import java.util.function.Supplier;

import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.impl.JidCreate;
import org.jxmpp.stringprep.XmppStringprepException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.controlml.payload.TrajectoryPayload;
import sabot.workbench.fleet.RobotState;

/**
 * The robots' telemetry (docs/CONTROLML.md section 6): the subscriptions to each followed robot's nodes, the items as
 * they arrive into the {@link RobotRegistry}, and the robot's plan (trajectory and goal) fetched when a mission starts.
 */
final class FleetTelemetry {

    /** The telemetry every followed robot is subscribed to. */
    static final List<Resource<?, ?>> TELEMETRY = List.of(Resources.POSITION, Resources.VELOCITY, Resources.MISSION,
            Resources.OBSTACLES, Resources.BATTERY);
    /** Most attempts to follow a robot whose nodes do not exist yet (it publishes within a second of coming online). */
    static final int FOLLOW_ATTEMPTS = 10;

    private static final Logger LOG = LoggerFactory.getLogger("sabot.workbench.controlml");

    private final Clock clock;
    private final RobotRegistry registry;
    private final FleetRequests requests;
    private final FleetTraffic traffic;
    private final FleetWatch watch;
    private final ScheduledExecutorService connector;
    private final Supplier<FleetSession> current;

    /**
     * @param connector the connection thread, where the subscriptions are made
     * @param current   the session now live, or null
     */
    FleetTelemetry(Clock clock, RobotRegistry registry, FleetRequests requests, FleetTraffic traffic,
            FleetWatch watch, ScheduledExecutorService connector, Supplier<FleetSession> current) {
        this.traffic = traffic;
        this.watch = watch;
        this.clock = clock;
        this.registry = registry;
        this.requests = requests;
        this.connector = connector;
        this.current = current;
    }

    /** Takes the session's telemetry items into the registry; before login, so +notify goes into its entity caps. */
    void listen(FleetSession s) {
        ControlMlManager m = s.manager();
        m.telemetry().addListener(Resources.POSITION, (device, pose) -> {
            long receivedNanos = System.nanoTime(); // the lag's receipt: monotonic (RobotState.poseLag)
            traffic.telemetry(device.toString());
            registry.update(device.toString(), r -> r.withPose(pose, clock.instant(), receivedNanos));
        });
        m.telemetry().addListener(Resources.VELOCITY, (device, v) -> {
            traffic.telemetry(device.toString());
            registry.update(device.toString(), r -> r.withVelocity(v.twist(), clock.instant()));
        });
        m.telemetry().addListener(Resources.OBSTACLES, (device, o) -> {
            traffic.telemetry(device.toString());
            registry.update(device.toString(), r -> r.withObstacles(o, clock.instant()));
        });
        m.telemetry().addListener(Resources.BATTERY, (device, b) -> {
            traffic.telemetry(device.toString());
            registry.update(device.toString(), r -> r.withBattery(b, clock.instant()));
        });
        m.telemetry().addListener(Resources.MISSION, (device, mission) -> {
            String jid = device.toString();
            traffic.telemetry(jid);
            RobotState before = registry.robot(jid);
            registry.update(jid, r -> r.withMission(mission, clock.instant()));
            if (before != null && newPlan(before.mission(), mission)) {
                fetchPlan(jid);
            }
        });
    }

    /**
     * @param before the robot's mission status as last known, or null
     * @return true when {@code now} has a plan that {@code before} had not: a mission started (or seen for the first
     *         time), or another leg of a mission of several targets (the next target, or a mission that replaced the
     *         one running)
     */
    static boolean newPlan(MissionStatus before, MissionStatus now) {
        if (!now.state().isActive()) {
            return false;
        }
        return before == null || before.state() != now.state() || before.current() != now.current() || !goals(before)
                .equals(goals(now));
    }

    private static List<Goal> goals(MissionStatus m) {
        return m.targets().stream().map(MissionTarget::goal).toList();
    }

    /**
     * Connection thread: subscribes explicitly to the robot's telemetry nodes (XEP-0060; {@code +notify} alone is not
     * dependable on ejabberd). A node that does not exist yet is asked for again a second later.
     */
    void follow(FleetSession s, String jid, int attempt) {
        if (current.get() != s) {
            return;
        }
        EntityBareJid robot;
        try {
            robot = JidCreate.entityBareFrom(jid);
        } catch (XmppStringprepException e) {
            return;
        }
        List<String> missing = new ArrayList<>();
        for (Resource<?, ?> r : TELEMETRY) {
            Outcome<Void> o = s.manager().telemetry().follow(robot, r);
            if (!o.isSuccess()) {
                missing.add(r.name() + " (" + o.errorOrNull() + ")");
            }
        }
        if (missing.isEmpty()) {
            LOG.info("following the telemetry of {}", jid);
        } else if (attempt + 1 < FOLLOW_ATTEMPTS) {
            connector.schedule(() -> follow(s, jid, attempt + 1), 1, TimeUnit.SECONDS);
        } else {
            LOG.warn("cannot subscribe to the telemetry of {}: {}", jid, missing);
        }
        fetchPlan(jid);
    }

    /**
     * A robot came online: its lease (what the views look at) is sent at once, without waiting for its turn on the
     * connection thread (a robot that restarted has forgotten it; the subscriptions of a thousand robots take a while).
     */
    void online(FleetSession s, String jid) {
        watch.online(s, jid);
    }

    /** Asks the robot for its planned trajectory and goal (a goal of none is not an error: no plan to show). */
    void fetchPlan(String jid) {
        CompletableFuture<TrajectoryPayload> path = requests.get(jid, Resources.TRAJECTORY);
        CompletableFuture<Goal> goal = requests.get(jid, Resources.GOAL);
        path.handle((t, e) -> t).thenCombine(goal.handle((g, e) -> g), (t, g) -> {
            registry.update(jid, r -> r.withPlan(t != null && !t.points().isEmpty() ? t : null, g));
            return null;
        });
    }
}
