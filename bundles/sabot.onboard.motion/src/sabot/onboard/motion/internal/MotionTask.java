package sabot.onboard.motion.internal;

import java.io.IOException;
import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Optional;
import java.util.concurrent.ConcurrentLinkedQueue;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import java.util.function.Consumer;

import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;
import org.osgi.service.component.annotations.Deactivate;
import org.osgi.service.component.annotations.Reference;
import org.osgi.service.component.annotations.ReferenceCardinality;
import org.osgi.service.component.annotations.ReferencePolicy;
import org.osgi.service.metatype.annotations.AttributeDefinition;
import org.osgi.service.metatype.annotations.Designate;
import org.osgi.service.metatype.annotations.ObjectClassDefinition;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.control.MotionLimits;
import sabot.controlml.ControlMlCondition;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.GridMap;
import sabot.controlml.payload.LimitsPayload;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.controlml.payload.Obstacle;
import sabot.controlml.payload.Obstacles;
import sabot.controlml.payload.PidGains;
import sabot.controlml.payload.PoseEstimate;
import sabot.controlml.payload.TrajectoryPayload;
import sabot.controlml.payload.TrajectoryPoint;
import sabot.controlml.payload.VelocityCommand;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.map.GridGeometry;
import sabot.model.map.OccupancyGrid;
import sabot.model.robot.BatteryState;
import sabot.model.robot.PassageClaim;
import sabot.model.robot.PeerRobot;
import sabot.model.robot.RobotDescription;
import sabot.model.robot.RobotDescriptions;
import sabot.onboard.motion.loop.BatteryGuard;
import sabot.onboard.motion.loop.ControlLoop;
import sabot.onboard.motion.loop.GuardSettings;
import sabot.onboard.motion.loop.LoopClock;
import sabot.onboard.motion.loop.LoopDefaults;
import sabot.onboard.motion.loop.LoopHost;
import sabot.onboard.motion.loop.LoopSettings;
import sabot.onboard.motion.loop.NavigationPlanner;
import sabot.onboard.motion.loop.PeerSettings;
import sabot.onboard.motion.loop.RobotBoards;
import sabot.onboard.task.NamedThreads;
import sabot.onboard.robot.CommandRefused;
import sabot.onboard.robot.MotionListener;
import sabot.onboard.robot.RobotMotion;
import sabot.onboard.session.FleetPeers;
import sabot.onboard.session.RobotSession;
import sabot.onboard.session.SessionListener;
import sabot.onboard.task.OnboardTask;
import sabot.pidstep.controlml.StepTest;

/**
 * Task {@code motion}: the robot's fixed-rate control loop and the {@link RobotMotion} service. Each period, on the
 * thread {@code sabot-control-loop}: commands queued by other threads are applied, the encoders are read (every
 * other period), the estimate updated, the safety checks run, the mode's controller computes a twist, the velocity
 * smoother bounds it, and the wheel speeds are written; in the periods without an encoder read, the inertial board,
 * one sonar sensor or the landmark board is read after the write (its wire time is budgeted, so the loop does not
 * overrun on it). Nothing in the loop waits on the
 * network; planning runs on the thread {@code sabot-planner} (a goal's first plan too: the request waits for it).
 * The loop itself is {@link ControlLoop}; this component is its host: it schedules it, queues the other threads'
 * commands for it, plans for it, publishes its state, and hands it one {@link LoopSettings} snapshot built from the
 * motion tasks' settings. Settings: {@link Config}.
 */
@Designate(ocd = MotionTask.Config.class, factory = false)
@Component(name = "sabot.task.motion", configurationPolicy = ConfigurationPolicy.REQUIRE,
        service = { OnboardTask.class, RobotMotion.class })
public final class MotionTask implements OnboardTask, RobotMotion {

    /** The task's settings: its Metatype description, generated from these annotations. */
    @ObjectClassDefinition(id = "sabot.task.motion", name = "Motion task", description = "The fixed-rate control "
            + "loop: encoders and inertial sample in, estimate, tracker, wheel speeds out.")
    public @interface Config {
        @AttributeDefinition(name = "Rate", description = "Control loop rate, Hz.", min = "5", max = "200")
        double rate() default LoopDefaults.RATE;

        @AttributeDefinition(name = "Board deadman", description = "The motor board stops the wheels by itself when "
                + "no set-point arrives for this long, s.", min = "0.05", max = "60")
        double boardDeadman() default 0.3;

        @AttributeDefinition(name = "Status period", description = "Seconds between two status log lines (0: none).",
                min = "0", max = "3600")
        double statusPeriod() default LoopDefaults.STATUS_PERIOD;

        @AttributeDefinition(name = "Stop on disconnect", description = "Brake when the XMPP connection is lost while "
                + "moving.")
        boolean stopOnDisconnect() default true;

        @AttributeDefinition(name = "Obstacle memory", description = "Seconds a sonar echo stays in the obstacle "
                + "list.", min = "0.1", max = "600")
        double obstacleMemory() default LoopDefaults.OBSTACLE_MEMORY;

        @AttributeDefinition(name = "Blocked lookahead", description = "Seconds of driving along the trajectory ahead "
                + "checked against obstacles.", min = "0.1", max = "60")
        double blockedLookahead() default LoopDefaults.BLOCKED_LOOKAHEAD;

        @AttributeDefinition(name = "Blocked clearance", description = "Clearance beyond the robot radius an obstacle "
                + "must keep from the path ahead, m.", min = "0", max = "2")
        double blockedClearance() default LoopDefaults.BLOCKED_CLEARANCE;

        @AttributeDefinition(name = "Goal tolerance", description = "Position tolerance at a goal that does not carry "
                + "its own, m.", min = "0.005", max = "5")
        double goalTolerance() default LoopDefaults.GOAL_TOLERANCE;

        @AttributeDefinition(name = "Guard margin", description = "Distance, m, the collision guard stops the robot "
                + "short of an obstacle it knows (map walls, sonar echoes), whatever commands it.", min = "0",
                max = "1")
        double guardMargin() default LoopDefaults.GUARD_MARGIN;

        @AttributeDefinition(name = "Guard reaction time", description = "Seconds from a command to the wheels "
                + "braking, counted by the collision guard as driving on at the commanded speed.", min = "0",
                max = "1")
        double guardReactionTime() default LoopDefaults.GUARD_REACTION_TIME;

        @AttributeDefinition(name = "Reverse speed", description = "Top speed backwards, m/s: no sensor looks behind "
                + "the robot (0: never reverse).", min = "0", max = "1")
        double reverseSpeed() default LoopDefaults.REVERSE_SPEED;

        @AttributeDefinition(name = "Battery low", description = "State of charge (0-1) below which the robot aborts "
                + "its mission and drives to the nearest of the map's docks (sabot_docks); below Battery charged.",
                min = "0", max = "1")
        double batteryLow() default LoopDefaults.BATTERY_LOW;

        @AttributeDefinition(name = "Battery charged", description = "State of charge (0-1) at which a robot "
                + "charging on its dock after a low battery is free again.", min = "0", max = "1")
        double batteryCharged() default LoopDefaults.BATTERY_CHARGED;

        @AttributeDefinition(name = "Peer memory", description = "Seconds another robot not heard from stays an "
                + "obstacle of the planner and the collision guard (the peers task follows the fleet's robots; "
                + "docs/USER-GUIDE.md, Other robots); after it, only the sonar sees it.", min = "1", max = "3600")
        double peerMemory() default LoopDefaults.PEER_MEMORY;

        @AttributeDefinition(name = "Passage approach", description = "Metres of the path ahead within which a "
                + "narrow passage of the map (sabot_passages) is asked for; the robot that yields stops about this "
                + "far short of it (docs/PASSAGES.md).", min = "0.3", max = "10")
        double passageApproach() default LoopDefaults.PASSAGE_APPROACH;

        @AttributeDefinition(name = "Passage timeout", description = "Seconds a robot waits for its turn at a narrow "
                + "passage before its mission fails.", min = "1", max = "3600")
        double passageTimeout() default LoopDefaults.PASSAGE_TIMEOUT;

        @AttributeDefinition(name = "Real-time priority", description = "SCHED_FIFO priority of the control loop's "
                + "thread (0: the ordinary policy); needs CAP_SYS_NICE, otherwise the log says why and the loop runs "
                + "at the ordinary policy.", min = "0", max = "99")
        int realtimePriority() default 0;

        @AttributeDefinition(name = "Timer slack", description = "How late the kernel may wake the control loop's "
                + "thread after a timed wait (a period, a board's answer), µs; Linux gives ordinary threads 50 µs to "
                + "group wake-ups.", min = "0.001", max = "50000")
        double timerSlack() default 1;
    }

    private static final Logger LOG = LoggerFactory.getLogger("sabot.motion");

    @Reference
    private RobotBoards boards;
    @Reference
    private LocalizerTask localizerTask;
    @Reference
    private PlannerTask plannerTask;
    @Reference
    private TrackerTask trackerTask;
    private volatile TeleopTask teleopTask;

    private final List<MotionListener> listeners = new CopyOnWriteArrayList<>();
    private final ConcurrentLinkedQueue<Consumer<ControlLoop>> commands = new ConcurrentLinkedQueue<>();
    private final SessionListener sessionListener = new SessionListener() {
        @Override
        public void online() {
            LOG.info("XMPP session online");
        }

        @Override
        public void offline(String reason) {
            if (config.stopOnDisconnect() && snapshot.moving()) {
                LOG.warn("XMPP connection lost while moving: braking ({})", reason);
                commands.add(l -> l.fault("XMPP connection lost while moving (" + reason + ")"));
            }
        }
    };

    private Config config;
    private RobotDescription robot;
    private MotionLimits physicalLimits;
    private volatile MotionLimits limits;
    private ScheduledExecutorService loopThread;
    private volatile ScheduledFuture<?> schedule;
    private ExecutorService plannerThread;
    private ExecutorService notifier;
    private ControlLoop loop;
    /** The low-battery rules carried out. */
    private DockingDuty docking;
    private MotorTuning tuning;
    /** What other threads read: the loop's state at the end of its last period or command. */
    private volatile ControlLoop.Snapshot snapshot;
    private volatile RobotSession session;
    /** The other robots (the peers task), or null while it does not run. */
    private volatile FleetPeers fleetPeers;
    private final LoopClock clock = LoopClock.SYSTEM;
    private final LoopHost host = new LoopHost() {
        @Override
        public void missionChanged(MissionStatus status) {
            MotionTask.this.missionChanged(status);
        }

        @Override
        public void planRequested(PlanRequest r) {
            plannerThread.execute(() -> {
                ControlLoop.Plan plan = loop.planPath(r.from(), r.via(), r.goal(), r.obstacles());
                commands.add(l -> l.replanned(r, plan));
            });
        }

        @Override
        public void applyPendingCommands() {
            applyCommands();
        }
    };

    @Activate
    void activate(Config c) throws IOException {
        this.config = c;
        this.robot = RobotDescriptions.defaults();
        this.physicalLimits = MotionLimits.of(robot);
        this.limits = physicalLimits;
        this.tuning = new MotorTuning(boards);
        boards.setBoardDeadman(Duration.ofMillis(Math.round(c.boardDeadman() * 1000)));
        boards.acknowledgeFaults();
        boards.brake(false);
        boards.writeWheelSpeeds(0, 0);
        notifier = Executors.newSingleThreadExecutor(NamedThreads.daemon("sabot-motion-events"));
        docking = new DockingDuty(new BatteryGuard(c.batteryLow(), c.batteryCharged(), plannerTask.docks()), notifier,
                () -> snapshot, new DockingDuty.Task() {
                    @Override
                    public void abort(String reason) throws CommandRefused {
                        command(new MissionStatus(MissionState.ABORTED, false, 0, reason));
                    }

                    @Override
                    public void startMission(List<MissionTarget> targets) throws CommandRefused {
                        MotionTask.this.startMission(targets, false);
                    }

                    @Override
                    public void chargingChanged() {
                        MissionStatus m = snapshot.mission();
                        for (MotionListener l : listeners) {
                            l.missionChanged(m); // on the notifier thread, in order with the mission's changes
                        }
                    }
                });
        plannerThread = Executors.newSingleThreadExecutor(NamedThreads.daemon("sabot-planner"));
        loop = new ControlLoop(host, clock, boards, robot, localizerTask.newLocalizer(plannerTask.landmarks()),
                plannerTask.planner(), trackerTask, settings(), limits);
        loop.peersFrom(this::peers, this::selfJid, new PeerSettings(c.peerMemory(), c.passageApproach(),
                c.passageTimeout()));
        loop.passages(plannerTask.passages());
        snapshot = loop.snapshot();
        loopThread = Executors.newSingleThreadScheduledExecutor(NamedThreads.daemon("sabot-control-loop",
                Thread.MAX_PRIORITY));
        long periodNanos = loop.timing().periodNanos();
        loopThread.execute(() -> timerSlack(c.timerSlack()));
        if (c.realtimePriority() > 0) {
            loopThread.execute(() -> realtime(c.realtimePriority()));
        }
        schedule = loopThread.scheduleAtFixedRate(this::tick, periodNanos, periodNanos, TimeUnit.NANOSECONDS);
        LOG.info("motion task started: control loop {} Hz, planner {}, tracker {}; bus time per period: wheel "
                + "write {} ms and, in turn, the encoder read {} ms or a sensor read of up to {} ms (wire times, "
                + "each after a {} ms inter-frame silence)", c.rate(), plannerTask.planner().algorithm(),
                trackerTask.config().controller(), ms(boards.wheelWriteWireTime()), ms(boards.encoderReadWireTime()),
                ms(boards.optionalReadWireTime()), ms(boards.interFrameDelay()));
    }

    /** @return the loop's settings, from the motion tasks' configurations as they are now */
    private LoopSettings settings() {
        Config m = config;
        PlannerTask.Config p = plannerTask.config();
        TrackerTask.Config t = trackerTask.config();
        TeleopTask teleop = teleopTask;
        return new LoopSettings(m.rate(), m.statusPeriod(), m.obstacleMemory(), m.blockedLookahead(),
                m.blockedClearance(), m.goalTolerance(), teleop != null, teleop != null ? teleop.config().timeout()
                        : LoopDefaults.DEADMAN, p.robotRadius(), p.blockedTimeout(), t.speedHeadroom(),
                t.accelerationHeadroom(), t.progressRadius(), t.progressTime(), t.settleTimeout(),
                localizerTask.settings(), new GuardSettings(m.guardMargin(), m.guardReactionTime(), m.reverseSpeed()));
    }

    @Reference(cardinality = ReferenceCardinality.OPTIONAL, policy = ReferencePolicy.DYNAMIC)
    void bindTeleop(TeleopTask t) {
        teleopTask = t;
        teleopChanged();
    }

    void unbindTeleop(TeleopTask t) {
        if (teleopTask == t) {
            teleopTask = null;
            teleopChanged();
        }
    }

    /** The teleop task came or went (or was reconfigured): the loop takes the joystick's new settings. */
    private void teleopChanged() {
        if (loop != null) {
            LoopSettings s = settings();
            commands.add(l -> l.settingsChanged(s));
        }
    }

    private static String ms(double seconds) {
        return String.format(Locale.ROOT, "%.2f", seconds * 1000);
    }

    private static void realtime(int priority) {
        String refused = RealtimeScheduling.applyToCurrentThread(priority);
        if (refused == null) {
            LOG.info("control loop thread at real-time priority {} (SCHED_FIFO)", priority);
        } else {
            LOG.warn("control loop thread left at the ordinary scheduling policy (motion.realtimePriority = {}): {}",
                    priority, refused);
        }
    }

    private static void timerSlack(double micros) {
        String refused = RealtimeScheduling.applyTimerSlackToCurrentThread(Math.max(1, Math.round(micros * 1000)));
        if (refused != null) {
            LOG.warn("control loop thread keeps its timer slack of {} ns (motion.timerSlack = {} µs): {}",
                    RealtimeScheduling.currentTimerSlack(), micros, refused);
        }
    }

    @Deactivate
    void deactivate() throws InterruptedException {
        loopThread.shutdown();
        loopThread.awaitTermination(2, TimeUnit.SECONDS);
        try {
            boards.writeWheelSpeeds(0, 0);
            boards.brake(true);
        } catch (IOException e) {
            LOG.warn("could not brake on stop: {}", e.getMessage());
        }
        plannerThread.shutdownNow();
        notifier.shutdown();
        LOG.info("motion task stopped, robot braked; control loop {}; joystick twist to wheel set-point {}; {}",
                loop.timing().summary(), loop.teleopLatency().describe(), loop.landmarkSummary());
    }

    @Reference(cardinality = ReferenceCardinality.OPTIONAL, policy = ReferencePolicy.DYNAMIC)
    void bindPeers(FleetPeers p) {
        fleetPeers = p;
    }

    void unbindPeers(FleetPeers p) {
        if (fleetPeers == p) {
            fleetPeers = null;
        }
    }

    /** @return the robot's bare JID, as the other robots know it; "" without a session */
    private String selfJid() {
        RobotSession s = session;
        return s == null ? "" : s.jid();
    }

    /** @return the robots the peers task follows; none while it does not run */
    private List<PeerRobot> peers() {
        FleetPeers p = fleetPeers;
        return p == null ? List.of() : p.peers();
    }

    @Reference(cardinality = ReferenceCardinality.OPTIONAL, policy = ReferencePolicy.DYNAMIC)
    void bindSession(RobotSession s) {
        this.session = s;
        s.addListener(sessionListener);
    }

    void unbindSession(RobotSession s) {
        s.removeListener(sessionListener);
        if (this.session == s) {
            this.session = null;
        }
    }

    /** Applies queued commands between two periods and writes a new joystick twist at once when there is time. */
    private void drainCommands() {
        try {
            applyCommands();
            loop.teleopWrite();
        } catch (RuntimeException e) {
            LOG.error("control loop error, braking", e);
            loop.fault("internal error: " + e);
        }
    }

    /** Applies the commands queued so far; on the loop's thread only (between periods, or mid-period by the loop). */
    void applyCommands() {
        Consumer<ControlLoop> command;
        boolean applied = false;
        while ((command = commands.poll()) != null) {
            command.accept(loop);
            applied = true;
        }
        if (applied) {
            // a caller waiting in apply() reads the new state as soon as its command has been taken
            snapshot = loop.snapshot();
            synchronized (commands) {
                commands.notifyAll();
            }
        }
    }

    private void tick() {
        long start = clock.nanoTime();
        // inside its run a periodic task's delay is the time since it was due (negative or zero): the executor's own
        // schedule, which the loop's jitter is measured against (the first run may come before the assignment)
        ScheduledFuture<?> s = schedule;
        long scheduled = s == null ? start : start + s.getDelay(TimeUnit.NANOSECONDS);
        try {
            applyCommands();
            snapshot = loop.tick(start, scheduled);
            docking.periodEnded(snapshot);
        } catch (RuntimeException e) {
            // A bug must not stop the loop's thread (scheduleAtFixedRate would end silently): brake and say why.
            LOG.error("control loop error, braking", e);
            loop.fault("internal error: " + e);
        }
    }

    /**
     * Called by the loop (its thread) when the mission's status changed: the new state is published at once, before
     * the loop logs it or listeners hear of it, so that whoever reacts reads it.
     */
    private void missionChanged(MissionStatus status) {
        snapshot = loop.snapshot();
        for (MotionListener l : listeners) {
            notifier.execute(() -> l.missionChanged(status));
        }
    }

    @Override
    public boolean charging() {
        return docking.charging();
    }

    /** Queues a command for the loop's next period. */
    private void enqueue(Consumer<ControlLoop> command) {
        commands.add(command);
    }

    /**
     * Queues a command and waits until the loop has applied it (at most a period, bounded by {@link #APPLY_TIMEOUT_MS}),
     * so that the caller's next read ({@code mission()}, {@code goal()}) sees its effect.
     */
    private void apply(Consumer<ControlLoop> command) throws CommandRefused {
        boolean[] done = new boolean[1];
        commands.add(loop -> {
            command.accept(loop);
            done[0] = true;
        });
        long deadline = System.nanoTime() + TimeUnit.MILLISECONDS.toNanos(APPLY_TIMEOUT_MS);
        synchronized (commands) {
            while (!done[0]) {
                long left = deadline - System.nanoTime();
                if (left <= 0) {
                    throw new CommandRefused(ControlMlCondition.DEVICE_FAULT, "the control loop did not take the "
                            + "command within " + APPLY_TIMEOUT_MS + " ms");
                }
                try {
                    TimeUnit.NANOSECONDS.timedWait(commands, left);
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                    throw new CommandRefused(ControlMlCondition.DEVICE_FAULT, "interrupted");
                }
            }
        }
    }

    /** Longest wait for the control loop to take a command, ms (it takes them at the start of every period). */
    private static final long APPLY_TIMEOUT_MS = 1000;

    // ------------------------------------------------------------------------------------------------ RobotMotion

    @Override
    public PoseEstimate pose() {
        return snapshot.pose();
    }

    @Override
    public Optional<PassageClaim> passage() {
        return snapshot.passage();
    }

    @Override
    public BatteryState battery() throws CommandRefused {
        ControlLoop.Snapshot s = snapshot;
        if (!s.batteryFault().isEmpty()) {
            throw new CommandRefused(ControlMlCondition.DEVICE_FAULT, s.batteryFault());
        }
        return s.battery().orElseThrow(() -> new CommandRefused(ControlMlCondition.DEVICE_FAULT,
                "the power board has not been read yet"));
    }

    @Override
    public VelocityCommand velocity() {
        return snapshot.velocity();
    }

    @Override
    public void relocalise(Pose2D pose) throws CommandRefused {
        requireFinite(pose);
        if (snapshot.moving()) {
            throw new CommandRefused(ControlMlCondition.INVALID_STATE, "the robot is moving: stop it before re-localising");
        }
        requireOnMap(pose.position(), "pose");
        apply(l -> l.relocalise(pose));
    }

    @Override
    public void teleop(Twist2D twist, Instant sent, Duration age) throws CommandRefused {
        TeleopTask t = teleopTask;
        if (t == null) {
            throw new CommandRefused(ControlMlCondition.UNSUPPORTED_OPERATION, "the teleop task is not running");
        }
        double maxAge = t.config().maxAge();
        if (age.toNanos() > maxAge * 1e9) {
            throw new CommandRefused(ControlMlCondition.STALE_COMMAND, "twist sent " + age.toMillis()
                    + " ms ago, longer than teleop.maxAge (" + Math.round(maxAge * 1000) + " ms): dropped");
        }
        if (!twist.isFinite()) {
            throw new CommandRefused(ControlMlCondition.INVALID_VALUE, "twist must be finite");
        }
        ControlLoop.Snapshot s = snapshot;
        if (s.mission().state() == MissionState.RUNNING || s.mission().state() == MissionState.PAUSED) {
            throw new CommandRefused(ControlMlCondition.INVALID_STATE,
                    "a mission is " + s.mission().state().name().toLowerCase() + ": abort it before driving by joystick");
        }
        if (s.mission().maintenance()) {
            throw new CommandRefused(ControlMlCondition.MAINTENANCE_LOCK, "the robot is in maintenance");
        }
        requireBoardsAnswer();
        double v = clamp(twist.linear(), Math.min(t.config().maxLinear(), limits.maxLinearSpeed()));
        double w = clamp(twist.angular(), Math.min(t.config().maxAngular(), limits.maxAngularSpeed()));
        Twist2D bounded = new Twist2D(v, w);
        long received = clock.nanoTime();
        enqueue(l -> l.teleop(bounded, received, sent));
        // on the loop's own thread, between two periods: takes the twist and writes it if the bus has the time
        try {
            loopThread.execute(this::drainCommands);
        } catch (RejectedExecutionException stopping) {
            // the task is stopping: the robot brakes anyway
        }
    }

    @Override
    public Optional<Goal> goal() {
        return snapshot.goal();
    }

    @Override
    public void navigateTo(Goal goal) throws CommandRefused {
        requireFinite(goal.pose());
        if (!(goal.positionTolerance() > 0) || !(goal.headingTolerance() > 0)) {
            throw new CommandRefused(ControlMlCondition.INVALID_VALUE, "goal tolerances must be > 0");
        }
        if (snapshot.mission().maintenance()) {
            throw new CommandRefused(ControlMlCondition.MAINTENANCE_LOCK, "the robot is in maintenance");
        }
        requireBoardsAnswer();
        requireOnMap(goal.pose().position(), "goal");
        Pose2D from = snapshot.pose().pose();
        List<Point2D> obstacles = obstaclePoints(snapshot.obstacles());
        ControlLoop.Plan plan = firstPlan(from, goal, obstacles);
        if (plan.refusal() != null) {
            throw new CommandRefused(ControlMlCondition.INVALID_VALUE, plan.refusal());
        }
        apply(l -> l.startMission(goal, plan));
        LOG.info("new goal ({}, {}, {}): path {} m", fmt(goal.pose().x()), fmt(goal.pose().y()),
                fmt(goal.pose().theta()), fmt(plan.length()));
    }

    @Override
    public void startMission(List<MissionTarget> targets, boolean queue) throws CommandRefused {
        if (targets.isEmpty() || targets.size() > MissionStatus.MAX_TARGETS) {
            throw new CommandRefused(ControlMlCondition.INVALID_VALUE, "a mission has 1.." + MissionStatus.MAX_TARGETS
                    + " targets, not " + targets.size());
        }
        ControlLoop.Snapshot s = snapshot;
        if (s.mission().maintenance()) {
            throw new CommandRefused(ControlMlCondition.MAINTENANCE_LOCK, "the robot is in maintenance");
        }
        requireBoardsAnswer();
        if (queue && s.mission().queued() >= MissionStatus.MAX_QUEUED) {
            throw new CommandRefused(ControlMlCondition.BUSY, "the queue holds " + MissionStatus.MAX_QUEUED
                    + " missions already");
        }
        List<Point2D> obstacles = obstaclePoints(s.obstacles());
        Pose2D from = s.pose().pose();
        for (int i = 0; i < targets.size(); i++) {
            Goal g = targets.get(i).goal();
            String which = "target " + (i + 1) + " of " + targets.size();
            requireFinite(g.pose());
            requireOnMap(g.pose().position(), which);
            ControlLoop.Plan plan = firstPlan(from, g, obstacles);
            if (plan.refusal() != null) {
                throw new CommandRefused(ControlMlCondition.INVALID_VALUE, which + " at (" + fmt(g.pose().x()) + ", "
                        + fmt(g.pose().y()) + "): " + plan.refusal());
            }
            from = g.pose();
        }
        if (queue) {
            boolean[] taken = new boolean[1];
            apply(l -> taken[0] = l.enqueue(targets));
            if (!taken[0]) {
                throw new CommandRefused(ControlMlCondition.BUSY, "the queue holds " + MissionStatus.MAX_QUEUED
                        + " missions already");
            }
        } else {
            apply(l -> l.startMission(targets));
        }
        LOG.info("mission of {} targets {}", targets.size(), queue ? "queued" : "started");
    }

    /**
     * Plans a new goal on the planner's thread (as every plan) and waits for it, at most {@link #PLAN_TIMEOUT_S}, so
     * that a goal the planner refuses is answered with the reason.
     */
    private ControlLoop.Plan firstPlan(Pose2D from, Goal goal, List<Point2D> obstacles) throws CommandRefused {
        Future<ControlLoop.Plan> plan;
        try {
            plan = plannerThread.submit(() -> loop.planPath(from, goal, obstacles));
        } catch (RejectedExecutionException stopping) {
            throw new CommandRefused(ControlMlCondition.INVALID_STATE, "the motion task is stopping");
        }
        try {
            return plan.get(PLAN_TIMEOUT_S, TimeUnit.SECONDS);
        } catch (TimeoutException e) {
            plan.cancel(true);
            throw new CommandRefused(ControlMlCondition.TIMEOUT, "no plan within " + PLAN_TIMEOUT_S + " s");
        } catch (ExecutionException e) {
            LOG.error("planning failed", e.getCause());
            throw new CommandRefused(ControlMlCondition.UNSPECIFIED, "planning failed: " + e.getCause());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new CommandRefused(ControlMlCondition.DEVICE_FAULT, "interrupted");
        }
    }

    /**
     * Longest wait for a goal's first plan, s: Smack's default reply timeout (5 s), after which the operator's request
     * has failed anyway.
     */
    private static final long PLAN_TIMEOUT_S = 5;

    @Override
    public TrajectoryPayload trajectory() {
        return snapshot.trajectory();
    }

    @Override
    public void follow(TrajectoryPayload trajectory) throws CommandRefused {
        if (trajectory.points().size() < 2) {
            throw new CommandRefused(ControlMlCondition.INVALID_VALUE, "a trajectory needs at least two points");
        }
        if (snapshot.mission().maintenance()) {
            throw new CommandRefused(ControlMlCondition.MAINTENANCE_LOCK, "the robot is in maintenance");
        }
        requireBoardsAnswer();
        for (TrajectoryPoint p : trajectory.points()) {
            requireOnMap(new Point2D(p.x(), p.y()), "trajectory point");
            if (Math.abs(p.v()) > limits.maxLinearSpeed() * 1.0001
                    || Math.abs(p.omega()) > limits.maxAngularSpeed() * 1.0001) {
                throw new CommandRefused(ControlMlCondition.INVALID_VALUE, "trajectory point at t = " + p.t()
                        + " s exceeds the motion limits (" + limits.maxLinearSpeed() + " m/s, "
                        + limits.maxAngularSpeed() + " rad/s)");
            }
        }
        List<Point2D> path = trajectory.points().stream().map(p -> new Point2D(p.x(), p.y())).toList();
        NavigationPlanner planner = plannerTask.planner();
        NavigationPlanner.Collision c = planner.firstCollision(path, obstaclePoints(snapshot.obstacles()));
        if (c != null) {
            TrajectoryPoint p = trajectory.points().get(c.point());
            throw new CommandRefused(ControlMlCondition.INVALID_VALUE, String.format(Locale.ROOT,
                    "trajectory point %d (t = %.2f s, %.2f, %.2f) collides: at (%.2f, %.2f) an obstacle is %.2f m "
                            + "from the robot's centre, inside its %.2f m radius", c.point(), p.t(), p.x(), p.y(),
                    c.at().x(), c.at().y(), c.clearance(), planner.robotRadius()));
        }
        apply(l -> l.followImposed(trajectory));
    }

    @Override
    public Obstacles obstacles() {
        return snapshot.obstacles();
    }

    @Override
    public GridMap map() {
        OccupancyGrid g = plannerTask.planner().map();
        GridGeometry geo = g.geometry();
        return new GridMap(geo.resolution(), geo.width(), geo.height(), geo.origin(), g.toArray());
    }

    @Override
    public void replaceMap(GridMap map) throws CommandRefused {
        if (snapshot.moving()) {
            throw new CommandRefused(ControlMlCondition.INVALID_STATE, "the robot is moving: replace the map at rest");
        }
        OccupancyGrid grid;
        try {
            grid = OccupancyGrid.of(new GridGeometry(map.width(), map.height(), map.resolution(), map.origin()),
                    map.cells());
        } catch (IllegalArgumentException e) {
            throw new CommandRefused(ControlMlCondition.INVALID_VALUE, e.getMessage());
        }
        plannerTask.planner().replaceMap(grid);
        LOG.info("map replaced: {} x {} cells of {} m", map.width(), map.height(), map.resolution());
    }

    @Override
    public LimitsPayload limits() {
        MotionLimits l = limits;
        return new LimitsPayload(l.maxLinearSpeed(), l.maxAngularSpeed(),
                l.maxLinearAcceleration(), l.maxAngularAcceleration());
    }

    @Override
    public void setLimits(LimitsPayload requested) throws CommandRefused {
        MotionLimits p = physicalLimits;
        check(requested.maxLinearSpeed(), p.maxLinearSpeed(), "maxLinearSpeed", "m/s");
        check(requested.maxAngularSpeed(), p.maxAngularSpeed(), "maxAngularSpeed", "rad/s");
        check(requested.maxLinearAcceleration(), p.maxLinearAcceleration(), "maxLinearAcceleration", "m/s2");
        check(requested.maxAngularAcceleration(), p.maxAngularAcceleration(), "maxAngularAcceleration", "rad/s2");
        // The smoother bounds each wheel's rim acceleration by a_lin; a lower angular bound lowers it accordingly.
        double linearAcceleration = Math.min(requested.maxLinearAcceleration(),
                requested.maxAngularAcceleration() * p.trackWidth() / 2);
        MotionLimits l = new MotionLimits(requested.maxLinearSpeed(), linearAcceleration, requested.maxAngularSpeed(),
                Math.min(p.maxLateralAcceleration(), requested.maxLinearAcceleration()), p.maxWheelRimSpeed(),
                p.trackWidth());
        this.limits = l;
        enqueue(loop -> loop.limitsChanged(l));
        LOG.info("motion limits set: {} m/s, {} rad/s, {} m/s2", l.maxLinearSpeed(), l.maxAngularSpeed(),
                l.maxLinearAcceleration());
    }

    @Override
    public PidGains gains() throws CommandRefused {
        return tuning.gains();
    }

    /**
     * Runs on the session's ordered request thread (Smack's sync IQ mode: one robot connection, its requests served
     * one after the other), so no cm.mission set can end maintenance and start a mission while the step runs: the
     * final brake cannot stop a mission. Other requests wait for the test (≈ 0.2 s, bounded by the recording); in
     * maintenance they cannot move the robot anyway. The loop's collision guard judges the step before it starts.
     */
    @Override
    public StepTest stepTest(int motor, double step) throws CommandRefused {
        return tuning.stepTest(motor, step, mission(), (m, s) -> {
            String[] blocked = new String[1];
            apply(l -> blocked[0] = l.stepTestBlocked(m, s));
            return blocked[0];
        });
    }

    @Override
    public PidGains setGains(PidGains gains) throws CommandRefused {
        return tuning.setGains(gains);
    }

    @Override
    public MissionStatus mission() {
        return snapshot.mission();
    }

    @Override
    public void command(MissionStatus command) throws CommandRefused {
        ControlLoop.Snapshot s = snapshot;
        MissionState current = s.mission().state();
        if (command.maintenance() != s.mission().maintenance()) {
            // a maintenance switch ignores the state; entering maintenance aborts a running or paused mission
            apply(l -> l.maintenance(command.maintenance(), command.detail()));
            return;
        }
        switch (command.state()) {
            case PAUSED -> {
                if (current != MissionState.RUNNING) {
                    throw new CommandRefused(ControlMlCondition.INVALID_STATE, "no running mission to pause");
                }
                apply(ControlLoop::pause);
            }
            case RUNNING -> {
                if (current != MissionState.PAUSED) {
                    throw new CommandRefused(ControlMlCondition.INVALID_STATE, "no paused mission to resume");
                }
                apply(ControlLoop::resume);
            }
            case ABORTED -> {
                if (current != MissionState.RUNNING && current != MissionState.PAUSED) {
                    throw new CommandRefused(ControlMlCondition.INVALID_STATE, "no mission to abort");
                }
                apply(l -> l.abort("aborted by " + (command.detail().isBlank() ? "the operator" : command.detail())));
            }
            default -> throw new CommandRefused(ControlMlCondition.INVALID_VALUE,
                    "a mission command is paused, running (resume) or aborted, not " + command.state().name()
                            .toLowerCase());
        }
    }

    @Override
    public void stop(String reason, boolean fault) {
        enqueue(l -> {
            if (fault) {
                l.fault(reason);
            } else {
                l.abort(reason);
            }
        });
    }

    @Override
    public void addListener(MotionListener listener) {
        listeners.add(listener);
    }

    @Override
    public void removeListener(MotionListener listener) {
        listeners.remove(listener);
    }

    // ----------------------------------------------------------------------------------------------------- task

    @Override
    public String name() {
        return "motion";
    }

    @Override
    public String status() {
        ControlLoop.Snapshot s = snapshot;
        return "mission " + s.mission().state().name().toLowerCase() + ", control loop " + s.timing();
    }

    private void requireBoardsAnswer() throws CommandRefused {
        String faulted = boards.faultedBoard();
        if (faulted != null) {
            throw new CommandRefused(ControlMlCondition.DEVICE_FAULT, "the " + faulted + " board does not answer");
        }
    }

    private void requireOnMap(Point2D p, String what) throws CommandRefused {
        if (plannerTask.planner().map().geometry().cellAt(p).isEmpty()) {
            throw new CommandRefused(ControlMlCondition.INVALID_VALUE,
                    what + " (" + fmt(p.x()) + ", " + fmt(p.y()) + ") is outside the map");
        }
    }

    private static void requireFinite(Pose2D p) throws CommandRefused {
        if (p == null || !p.isFinite()) {
            throw new CommandRefused(ControlMlCondition.INVALID_VALUE, "pose must be finite");
        }
    }

    private static void check(double value, double physical, String name, String unit) throws CommandRefused {
        if (!(value > 0) || value > physical * (1 + 1e-9)) {
            throw new CommandRefused(ControlMlCondition.INVALID_VALUE,
                    name + " must be in (0, " + physical + "] " + unit + " (the robot's physical limit), was " + value);
        }
    }

    static List<Point2D> obstaclePoints(Obstacles o) {
        List<Point2D> points = new ArrayList<>(o.obstacles().size());
        for (Obstacle x : o.obstacles()) {
            points.add(new Point2D(x.x(), x.y()));
        }
        return points;
    }

    static double clamp(double v, double bound) {
        return Math.max(-bound, Math.min(bound, v));
    }

    private static String fmt(double v) {
        return ControlLoop.fmt(v);
    }
}
