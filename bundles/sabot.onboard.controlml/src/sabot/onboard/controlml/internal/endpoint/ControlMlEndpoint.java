package sabot.onboard.controlml.internal.endpoint;

import java.time.Instant;
import java.util.ArrayList;
import java.util.Comparator;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.function.Supplier;

import org.osgi.framework.Bundle;
import org.osgi.framework.ServiceReference;
import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;
import org.osgi.service.component.annotations.Deactivate;
import org.osgi.service.component.annotations.Reference;
import org.osgi.service.component.annotations.ReferenceCardinality;
import org.osgi.service.component.annotations.ReferencePolicy;
import org.osgi.service.component.annotations.ReferencePolicyOption;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlError;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.Request;
import sabot.controlml.PresenceLevel;
import sabot.controlml.Resource;
import sabot.controlml.ResourceRegistry;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.pidstep.controlml.PidStep;
import sabot.controlml.TelemetryLeases;
import sabot.controlml.payload.TelemetryRates;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.PassageStatus;
import sabot.controlml.payload.TaskInfo;
import sabot.controlml.payload.TaskList;
import sabot.model.robot.BatteryState;
import sabot.onboard.controlml.internal.session.ControlMlSettings;
import sabot.onboard.robot.CommandRefused;
import sabot.onboard.robot.MotionListener;
import sabot.onboard.robot.RobotMotion;
import sabot.onboard.session.RobotSession;
import sabot.onboard.task.OnboardTask;

/**
 * The robot's ControlML endpoint: serves the resources of {@code docs/CONTROLML.md} section 4 (all but
 * {@code cm.fs.*}, which the remote FS task serves) on the session's {@link ControlMlManager} from the robot's
 * {@link RobotMotion}, publishes {@code cm.position}, {@code cm.velocity}, {@code cm.mission} and {@code cm.obstacles}
 * as PEP telemetry while the session is online, and sets the robot's presence level from its mission.
 * <p>
 * It shares the configuration of the {@code controlml} task (PID {@code sabot.task.controlml}, Metatype with the
 * session's settings) and reads its telemetry rates from it. Handlers are registered once, on activation: the session
 * keeps one connection object across reconnections, and the manager's handlers belong to that object. Every handler
 * returns at once from the motion's cached state, except {@code cm.pid}, which costs a few bus transactions.
 * Behaviour for operators: "The onboard endpoint" in {@code docs/CONTROLML.md}.
 */
@Component(name = ControlMlEndpoint.COMPONENT_NAME, configurationPid = ControlMlEndpoint.CONFIGURATION_PID,
        configurationPolicy = ConfigurationPolicy.REQUIRE, service = {})
public final class ControlMlEndpoint {

    /** The component's name. */
    public static final String COMPONENT_NAME = "sabot.endpoint";
    /** The configuration it shares with the session: the {@code controlml} task's. */
    public static final String CONFIGURATION_PID = OnboardTask.PID_PREFIX + "controlml";

    /** The resources this endpoint serves (the remote FS task serves {@code cm.fs.*}). */
    static final List<Resource<?, ?>> SERVED = List.of(Resources.POSITION, Resources.VELOCITY, Resources.GOAL,
            Resources.TRAJECTORY, Resources.MAP, Resources.OBSTACLES, Resources.BATTERY, Resources.PASSAGE,
            Resources.PID, Resources.LIMITS, Resources.MISSION, Resources.TASKS);

    /** The {@code state} values a {@code cm.mission} set may ask for, besides a maintenance switch. */
    static final Set<MissionState> MISSION_COMMANDS = Set.of(MissionState.PAUSED, MissionState.RUNNING,
            MissionState.ABORTED);

    private static final Logger LOG = LoggerFactory.getLogger(ControlMlEndpoint.class);

    private final RobotSession session;
    private final RobotMotion motion;
    private final ControlMlSettings.Config config;
    private final Map<ServiceReference<OnboardTask>, OnboardTask> tasks = new ConcurrentHashMap<>();
    /** The telemetry publications and their leases (cm.telemetry); guarded by this. */
    private TelemetryLeases leases;
    private final MotionListener presence = this::missionChanged;
    private volatile ControlMlManager manager;
    /** {@code cm.pid.step} in the session's registry: not a resource of the protocol, this robot adds it. */
    private ResourceRegistry.Registration stepTestRegistration;
    private PresenceLevel shownLevel;
    private String shownReason;

    /**
     * @param session the robot's XMPP session
     * @param motion  the robot's motion (the control loop)
     * @param config  the {@code controlml} task's settings (the endpoint reads the telemetry rates)
     */
    @Activate
    public ControlMlEndpoint(@Reference(name = "session") RobotSession session,
            @Reference(name = "motion") RobotMotion motion, ControlMlSettings.Config config) {
        this.session = session;
        this.motion = motion;
        this.config = config;
        checkRate("positionRate", config.positionRate());
        checkRate("velocityRate", config.velocityRate());
        checkRate("missionRate", config.missionRate());
        checkRate("obstaclesRate", config.obstaclesRate());
        checkRate("batteryRate", config.batteryRate());
        checkRate("passageRate", config.passageRate());
        checkRate("baseRate", config.baseRate());
        if (!(config.leaseMax() >= 1 && config.leaseMax() <= TelemetryRates.MAX_LEASE_S)) {
            throw new IllegalArgumentException("controlml.leaseMax must be 1 to " + TelemetryRates.MAX_LEASE_S
                    + " s, was " + config.leaseMax());
        }
    }

    private static void checkRate(String setting, double hz) {
        if (!(hz >= 0 && hz <= ControlMlSettings.Config.MAX_RATE_HZ)) {
            throw new IllegalArgumentException("controlml." + setting + " must be 0 (off) to "
                    + ControlMlSettings.Config.MAX_RATE_HZ + " Hz, was " + hz);
        }
    }

    /** Registers the handlers, starts telemetry and shows the mission's presence. */
    @Activate
    void activate() {
        manager = session.controlMl();
        stepTestRegistration = manager.resources().register(PidStep.RESOURCE);
        registerHandlers(manager);
        synchronized (this) {
            leases = manager.telemetry().serveLeases(config.leaseMax());
            // every node at the base rate too: a watcher's explicit subscription needs the node to exist (section 6)
            publish(Resources.POSITION, motion::pose, config.positionRate());
            publish(Resources.VELOCITY, motion::velocity, config.velocityRate());
            publish(Resources.MISSION, motion::mission, config.missionRate());
            publish(Resources.OBSTACLES, motion::obstacles, config.obstaclesRate());
            // no reading yet, or the power board failing: a skipped tick (a get says why)
            publish(Resources.BATTERY, this::batteryOrNull, config.batteryRate());
            publish(Resources.PASSAGE, this::passage, config.passageRate());
        }
        motion.addListener(presence);
        showCurrentMission(); // the listener reports changes only
        LOG.info("ControlML endpoint serving {} resources for {}; telemetry while leased (at most {} s): position {} "
                + "Hz, velocity {} Hz, mission {} Hz, obstacles {} Hz, battery {} Hz, passage {} Hz; else {} Hz",
                SERVED.size(), session.jid(), config.leaseMax(), config.positionRate(), config.velocityRate(), config
                        .missionRate(), config.obstaclesRate(), config.batteryRate(), config.passageRate(), config
                                .baseRate());
    }

    /** Stops telemetry and presence updates and unregisters the handlers. */
    @Deactivate
    void deactivate() {
        // commands stop first; the listener goes last, so that its removal tells the robot the endpoint is gone
        for (Resource<?, ?> r : SERVED) {
            manager.removeHandlers(r);
        }
        manager.removeHandlers(PidStep.RESOURCE);
        stepTestRegistration.close();
        synchronized (this) {
            leases.close(); // its publications and cm.telemetry's handlers
            leases = null;
        }
        motion.removeListener(presence);
        LOG.info("ControlML endpoint of {} stopped", session.jid());
    }

    /** A task service came up; listed by {@code cm.tasks}. */
    @Reference(name = "tasks", service = OnboardTask.class, cardinality = ReferenceCardinality.MULTIPLE,
            policy = ReferencePolicy.DYNAMIC, policyOption = ReferencePolicyOption.GREEDY)
    void addTask(OnboardTask task, ServiceReference<OnboardTask> reference) {
        tasks.put(reference, task);
    }

    void removeTask(OnboardTask task, ServiceReference<OnboardTask> reference) {
        tasks.remove(reference);
    }

    // ---------------------------------------------------------------------------------------------- handlers

    private void registerHandlers(ControlMlManager m) {
        m.onGet(Resources.POSITION, (request, none) -> Outcome.success(motion.pose()));
        m.onSet(Resources.POSITION, (request, estimate) -> apply(() -> motion.relocalise(estimate.pose())));
        m.onGet(Resources.VELOCITY, (request, none) -> Outcome.success(motion.velocity()));
        m.onSet(Resources.VELOCITY, (request, twist) -> apply(() -> motion.teleop(twist.twist(), twist.time(),
                request.age())));
        m.onGet(Resources.GOAL, (request, none) -> goal());
        m.onSet(Resources.GOAL, (request, goal) -> apply(() -> motion.navigateTo(goal)));
        m.onGet(Resources.TRAJECTORY, (request, none) -> Outcome.success(motion.trajectory()));
        m.onSet(Resources.TRAJECTORY, (request, trajectory) -> apply(() -> motion.follow(trajectory)));
        m.onGet(Resources.MAP, (request, none) -> Outcome.success(motion.map()));
        m.onSet(Resources.MAP, (request, map) -> apply(() -> motion.replaceMap(map)));
        m.onGet(Resources.OBSTACLES, (request, none) -> Outcome.success(motion.obstacles()));
        m.onGet(Resources.BATTERY, (request, none) -> read(motion::battery));
        m.onGet(Resources.PASSAGE, (request, none) -> Outcome.success(passage()));
        m.onGet(Resources.PID, (request, none) -> read(motion::gains));
        m.onSet(Resources.PID, (request, gains) -> read(() -> motion.setGains(gains)));
        m.onGet(Resources.LIMITS, (request, none) -> Outcome.success(motion.limits()));
        m.onSet(Resources.LIMITS, (request, limits) -> apply(() -> motion.setLimits(limits)));
        m.onGet(Resources.MISSION, (request, none) -> Outcome.success(motion.mission()));
        m.onSet(Resources.MISSION, (request, command) -> commandMission(request, command));
        m.onGet(Resources.TASKS, (request, none) -> Outcome.success(taskList()));
        m.onSet(PidStep.RESOURCE, (request, test) -> read(() -> motion.stepTest(test.motor(), test.step())));
    }

    /** A robot command without a value to answer. */
    @FunctionalInterface
    private interface Command {
        void run() throws CommandRefused;
    }

    /** A robot call that answers a value (and may be refused). */
    @FunctionalInterface
    private interface Reading<T> {
        T get() throws CommandRefused;
    }

    private static <T> Outcome<T> apply(Command command) {
        try {
            command.run();
            return Outcome.done();
        } catch (CommandRefused refused) {
            return refusal(refused);
        }
    }

    private static <T> Outcome<T> read(Reading<T> reading) {
        try {
            return Outcome.success(reading.get());
        } catch (CommandRefused refused) {
            return refusal(refused);
        }
    }

    private static <T> Outcome<T> refusal(CommandRefused refused) {
        return Outcome.failure(ControlMlError.of(refused.condition(), refused.getMessage()));
    }

    private PassageStatus passage() {
        return new PassageStatus(Instant.now(), motion.passage());
    }

    private BatteryState batteryOrNull() {
        try {
            return motion.battery();
        } catch (CommandRefused refused) {
            return null;
        }
    }

    /** Without a goal there is nothing true to answer with: a pose would look like a target the robot does not have. */
    private Outcome<Goal> goal() {
        Optional<Goal> goal = motion.goal();
        if (goal.isEmpty()) {
            return Outcome.failure(ControlMlCondition.INVALID_STATE,
                    "no goal: the robot has had no mission to a goal since it started");
        }
        return Outcome.success(goal.get());
    }

    /**
     * A set is one command: when {@code maintenance} differs from the robot's mode it switches maintenance mode (and
     * {@code state} is not looked at); otherwise {@code state} must be a transition (paused, running, aborted). The
     * robot decides whether the transition fits its state. A maintenance switch needs the maintainer role (the
     * resource's other commands the operator's).
     */
    private Outcome<MissionStatus> commandMission(Request request, MissionStatus command) {
        boolean maintenanceSwitch = command.maintenance() != motion.mission().maintenance();
        if (maintenanceSwitch && !request.role().includes(Role.MAINTAINER)) {
            return Outcome.failure(ControlMlCondition.SET_NOT_PERMITTED, request.from().asBareJid() + " is "
                    + request.role().withArticle() + " on this device; switching maintenance " + (command.maintenance()
                            ? "on" : "off") + " needs the maintainer role");
        }
        if (!command.targets().isEmpty()) {
            if (maintenanceSwitch) {
                return Outcome.failure(ControlMlCondition.INVALID_VALUE, "a mission of targets and a maintenance "
                        + "switch are two commands: send them apart");
            }
            if (command.state() != MissionState.RUNNING && command.state() != MissionState.QUEUED) {
                return Outcome.failure(ControlMlCondition.INVALID_VALUE, "a mission of targets is started with state "
                        + "running (now) or queued (after the others), not '" + command.state().code() + "'");
            }
            return apply(() -> motion.startMission(command.targets(), command.state() == MissionState.QUEUED));
        }
        if (!maintenanceSwitch && !MISSION_COMMANDS.contains(command.state())) {
            return Outcome.failure(ControlMlCondition.INVALID_VALUE, "state '" + command.state().code()
                    + "' is not a command: send paused, running or aborted, a mission with targets, or switch "
                    + "maintenance");
        }
        return apply(() -> motion.command(command));
    }

    private TaskList taskList() {
        List<TaskInfo> list = new ArrayList<>();
        for (Map.Entry<ServiceReference<OnboardTask>, OnboardTask> e : tasks.entrySet()) {
            Bundle bundle = e.getKey().getBundle();
            if (bundle != null) { // null once unregistered: the unbind follows
                list.add(new TaskInfo(e.getValue().name(), bundle.getSymbolicName(), bundle.getVersion().toString(),
                        bundleState(bundle)));
            }
        }
        list.sort(Comparator.comparing(TaskInfo::name));
        return new TaskList(list);
    }

    /** The {@code cm.tasks} state of a task's bundle (the codes of the resource's {@code state} category). */
    static String bundleState(Bundle bundle) {
        return switch (bundle.getState()) {
            case Bundle.INSTALLED -> "installed";
            case Bundle.RESOLVED -> "resolved";
            case Bundle.STARTING -> "starting";
            case Bundle.STOPPING -> "stopping";
            default -> "active";
        };
    }

    // ---------------------------------------------------------------------------------------------- telemetry

    /** Publishes a resource at the base rate, faster while leased, up to {@code fullHz} (0: never). */
    private <T> void publish(Resource<T, ?> resource, Supplier<T> read, double fullHz) {
        if (fullHz > 0) {
            leases.offer(resource, new OnlineSource<>(resource, read), Math.min(config.baseRate(), fullHz), fullHz);
        }
    }

    /**
     * A telemetry source that gives nothing while the session is offline (the manager skips a null tick, so an
     * offline robot sends nothing and logs nothing) and turns a failing read into a skipped tick: an exception would
     * end the manager's fixed-rate task for good.
     */
    private final class OnlineSource<T> implements Supplier<T> {
        private final Resource<T, ?> resource;
        private final Supplier<T> read;
        private boolean failing; // only the manager's one telemetry thread calls get()

        OnlineSource(Resource<T, ?> resource, Supplier<T> read) {
            this.resource = resource;
            this.read = read;
        }

        @Override
        public T get() {
            if (!session.isOnline()) {
                return null;
            }
            try {
                T value = read.get();
                if (failing) {
                    LOG.info("{} telemetry readable again", resource);
                    failing = false;
                }
                return value;
            } catch (RuntimeException e) {
                if (!failing) { // once per failing spell, not at the publication rate
                    LOG.warn("{} telemetry skipped: reading it failed", resource, e);
                    failing = true;
                }
                return null;
            }
        }
    }

    // ---------------------------------------------------------------------------------------------- presence

    /** The presence's text while the robot charges on its dock after a low battery (docs/CONTROLML.md section 7). */
    static final String CHARGING = "charging";

    /**
     * Free when idle, done or aborted; busy running or paused; away in maintenance, after a failure, or while charging
     * on the dock after a low battery.
     */
    static PresenceLevel presenceOf(MissionStatus mission, boolean charging) {
        if (mission.maintenance() || charging) {
            return PresenceLevel.AWAY;
        }
        return switch (mission.state()) {
            case RUNNING, PAUSED -> PresenceLevel.BUSY;
            case FAILED -> PresenceLevel.AWAY;
            case IDLE, DONE, ABORTED, QUEUED -> PresenceLevel.FREE;
        };
    }

    /** The presence's status text: "charging" on the dock after a low battery, the mission's detail, else the level's. */
    static String reasonOf(MissionStatus mission, boolean charging) {
        if (charging && !mission.maintenance()) {
            return CHARGING;
        }
        if (!mission.detail().isBlank()) {
            return mission.detail();
        }
        return mission.maintenance() ? "maintenance" : mission.state().code();
    }

    /** Read under the lock: a change reported meanwhile must not be overwritten by an older state. */
    private synchronized void showCurrentMission() {
        missionChanged(motion.mission());
    }

    /**
     * Progress bands change the mission too: presence is sent only when its level or text changes. Synchronized with
     * {@link #showCurrentMission}.
     */
    private synchronized void missionChanged(MissionStatus mission) {
        boolean charging = motion.charging();
        PresenceLevel level = presenceOf(mission, charging);
        String reason = reasonOf(mission, charging);
        if (level == shownLevel && reason.equals(shownReason)) {
            return;
        }
        shownLevel = level;
        shownReason = reason;
        session.setPresence(level, reason);
    }
}
