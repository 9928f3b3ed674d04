package sabot.onboard.motion.loop;

import java.io.IOException;
import java.time.Duration;
import java.time.Instant;
import java.util.List;
import java.util.Locale;
import java.util.Optional;
import java.util.function.Supplier;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.control.ControlCommand;
import sabot.control.DifferentialDrive;
import sabot.control.GoalChecker;
import sabot.control.MotionLimits;
import sabot.control.ProgressChecker;
import sabot.control.TrackingController;
import sabot.control.TurnInPlace;
import sabot.control.VelocitySmoother;
import sabot.control.WheelSpeeds;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.controlml.payload.Obstacles;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.controlml.payload.TrajectoryPayload;
import sabot.controlml.payload.VelocityCommand;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.map.Passage;
import sabot.model.path.Trajectory;
import sabot.model.path.TrajectorySample;
import sabot.model.robot.BatteryState;
import sabot.model.robot.PassageClaim;
import sabot.model.robot.PeerRobot;
import sabot.model.robot.RobotDescription;
import sabot.planner.PlanResult;
import sabot.planner.costmap.MovingObstacle;

/**
 * The robot's control loop: its state and one period of it ({@link #tick}), in plain Java. Whoever runs it (the
 * {@code motion} task on the robot, a test, the motion simulation) gives it a {@link LoopHost} (plan requests, mission
 * events, queued commands), a {@link LoopClock}, the {@link RobotBoards}, the estimator, the planner and the control
 * laws, and one {@link LoopSettings} snapshot per configuration change. Every method runs on the loop's thread, except
 * {@link #planPath}, which only reads immutable inputs and the planner (serialised by itself), and
 * {@link #peersFrom}.
 * <p>
 * The other robots ({@link #peersFrom}: the peers task's snapshot) are obstacles like the sonar's echoes: planned
 * around with their predicted sweep, checked against the path ahead, and counted by the collision guard.
 * <p>
 * One deadman: while a joystick drives, the robot brakes when no twist has been received for
 * {@link LoopSettings#deadman()} seconds (judged on the twist's receive time, as ros2_control's
 * {@code cmd_vel_timeout}). The velocity smoother is given the same timeout; it is fed a target every period, so its
 * own timeout would act only if the loop stopped feeding it. The motor board's own deadman (the motion task's
 * {@code boardDeadman}) stops the wheels if the loop stops writing altogether.
 */
public final class ControlLoop {

    private static final Logger LOG = LoggerFactory.getLogger("sabot.motion");
    private static final Logger STATUS = LoggerFactory.getLogger("sabot.status");

    /** Heading error (rad) above which the robot turns in place before it follows a new trajectory. */
    static final double ALIGN_THRESHOLD = 0.35;
    /** Heading error (rad) at which the turn in place ends. */
    static final double ALIGNED = 0.08;
    /** Yaw rate (rad/s) below which a turn in place counts as ended (the tracker takes the rest). */
    static final double ALIGNED_RATE = 0.5;
    /** Fraction of the yaw rate and acceleration limits a turn in place uses (the rest absorbs a late period). */
    static final double TURN_FRACTION = 0.8;
    /** Gain of the turn's proportional zone near the target, 1/s (the braking curve above it). */
    static final double TURN_GAIN = 5.0;
    /** Seconds between two attempts to plan around a blocked path. */
    static final double REPLAN_RETRY = 1.0;
    /** The stabilizer hands over to the turn in place inside this fraction of the position tolerance. */
    static final double SETTLE_POSITION_FRACTION = 0.5;
    /** The turn in place aims inside this fraction of the heading tolerance. */
    static final double SETTLE_HEADING_FRACTION = 0.5;
    /** A slave's answer comes this much later than its wire time at most, in the loop's budget (turnaround). */
    static final double WIRE_TIME_FACTOR = 1.2;
    /** Time kept free at the end of a period, s: the next start's wake-up jitter. */
    static final double PERIOD_MARGIN = 0.001;
    /** What the loop is doing. */
    public enum Mode {
        IDLE, TELEOP, ALIGN, FOLLOW, SETTLE, BLOCKED, PAUSED, FAULT,
        /** stands on a mission's target: its wait, or the next leg's plan */
        WAIT,
        /** stands short of a narrow passage of the map until its turn ({@link PassageRule}) */
        YIELD
    }

    /** A planned path turned into a trajectory, or why not ({@code refusal}, for the operator). */
    public record Plan(Trajectory trajectory, double length, String refusal) {
    }

    /**
     * What other threads read: the loop's state at the end of a period or a command. Immutable.
     *
     * @param battery      the power board's last good reading, empty before the first
     * @param batteryFault why the power board's last read failed, for a person; empty when it succeeded
     * @param passage      this robot's claim on a narrow passage ({@code cm.passage}), empty for none
     */
    public record Snapshot(PoseEstimate pose, VelocityCommand velocity, MissionStatus mission, Optional<Goal> goal,
            TrajectoryPayload trajectory, Obstacles obstacles, boolean moving, LoopTiming.Summary timing, Mode mode,
            Optional<BatteryState> battery, String batteryFault, Optional<PassageClaim> passage) {
    }

    private final LoopHost host;
    private final LoopClock clock;
    private final RobotBoards boards;
    private final DifferentialDrive drive;
    private final Localizer localizer;
    private final NavigationPlanner planner;
    private final LoopControllers controllers;
    private final long t0;
    private final LoopTiming timing;
    private final EchoMemory echoes;
    /** The other robots, as the peers task hears them. */
    private final PeerField peers = new PeerField();
    /** This robot's claims on the map's narrow passages. */
    private final PassageRule passages = new PassageRule();
    private volatile Supplier<String> self = () -> "";
    private volatile PeerSettings peerSettings = LoopDefaults.peers();
    /** Trajectory time at which the robot began to yield (the path ahead is judged from there). */
    private double yieldTau;
    private String yieldReason = "";
    private final SensorRounds sensors;
    private final LoopGuard guard;

    /** Replaced on the loop's thread, read by planning on the planner's too. */
    private volatile LoopSettings settings;
    /** Written on the loop's thread, read by planning on the planner's. */
    private volatile MotionLimits limits;
    private VelocitySmoother smoother;
    private TrackingController tracker;
    private TrackingController stabilizer;
    private TurnInPlace turn;
    private GoalChecker goalChecker;
    private ProgressChecker progressChecker;

    private Mode mode = Mode.IDLE;
    private Mode pausedFrom;
    /** The status the operator reads, the mission of targets being run and the queue. */
    private final MissionLedger missions;
    private Goal goal;
    /** The goal of the leg whose plan the loop waits for (the next target's), or null. */
    private Goal legPlanFor;
    /** When the robot's wait on a target ends (loop time), or NaN while none. */
    private double waitUntil = Double.NaN;
    /** A paused wait's remaining seconds. */
    private double waitLeft;
    private Trajectory trajectory;
    private TrajectoryPayload trajectoryPayload = new TrajectoryPayload(Instant.EPOCH, List.of());
    private double trajectoryStart;
    private double modeSince;
    private double lastReplan = Double.NEGATIVE_INFINITY;
    private boolean replanPending;
    private Twist2D teleopTwist = Twist2D.ZERO;
    private double teleopTime = Double.NEGATIVE_INFINITY;
    /** When the operator sent the newest twist not yet written to the wheels (null once written). */
    private Instant teleopSent;
    private final MicrosHistogram teleopLatency = new MicrosHistogram();
    private boolean braked;
    private boolean settlingReported;
    private boolean readyReported;
    /** Set once the settle phase reached the goal's position; the turn in place follows. */
    private boolean positionSettled;
    private double lastStatus = Double.NEGATIVE_INFINITY;
    private Pose2D pose;
    private double[] velocity = { 0, 0 };

    /**
     * @param host        plan requests, mission events, queued commands
     * @param clock       the loop's time; its origin is the loop's start
     * @param boards      the robot's bus
     * @param robot       the drive's geometry
     * @param localizer   the pose estimate, at the configured start
     * @param planner     plans on the static map plus the remembered echoes
     * @param controllers the tracking controller and point stabilizer
     * @param settings    the configuration's snapshot
     * @param limits      the motion limits in force (written to the motor board)
     */
    public ControlLoop(LoopHost host, LoopClock clock, RobotBoards boards, RobotDescription robot, Localizer localizer,
            NavigationPlanner planner, LoopControllers controllers, LoopSettings settings, MotionLimits limits) {
        this.host = host;
        this.missions = new MissionLedger(host);
        this.clock = clock;
        this.t0 = clock.nanoTime();
        this.boards = boards;
        this.drive = DifferentialDrive.of(robot);
        this.localizer = localizer;
        this.planner = planner;
        this.controllers = controllers;
        this.settings = settings;
        this.timing = new LoopTiming(settings.periodNanos());
        this.echoes = new EchoMemory(planner);
        this.guard = new LoopGuard(planner, echoes, peers);
        this.sensors = new SensorRounds(boards, localizer, echoes, this::now, clock::now);
        this.pose = settings.localizer().start();
        limitsChanged(limits);
    }

    private double now() {
        return (clock.nanoTime() - t0) * 1e-9;
    }

    public LoopTiming timing() {
        return timing;
    }

    /** @return joystick twist sent → wheel set-point written, as measured so far */
    public MicrosHistogram teleopLatency() {
        return teleopLatency;
    }

    /** A new configuration's snapshot; takes effect from the next period (the rate is fixed at the start). */
    public void settingsChanged(LoopSettings s) {
        this.settings = s;
        guard.configure(s, limits);
    }

    /**
     * Where the loop hears of the other robots (the peers task's snapshot, read once a period and at each plan), who
     * this robot is to them, and how it treats them; thread-safe.
     *
     * @param source   the robots followed; {@code List::of} for none
     * @param self     this robot's bare JID (two requests for a passage at one instant: the smaller JID goes
     *                 first); "" while unknown
     * @param settings memory, passage approach and timeout
     */
    public void peersFrom(Supplier<List<PeerRobot>> source, Supplier<String> self, PeerSettings settings) {
        peers.from(source, settings.memory());
        this.self = self;
        this.peerSettings = settings;
    }

    /** The map's narrow passages, where robots pass one at a time (loop thread; a new map gives up the claim). */
    public void passages(List<Passage> list) {
        passages.passages(list);
    }

    /** @return what the collision guard last did to a command, e.g. {@code stopped: obstacle 0.31 m ahead}; "" */
    public String guardStatus() {
        return guard.status();
    }

    // --------------------------------------------------------------------------------------------- one period

    /**
     * One period of the loop.
     *
     * @param start     the clock's nanoTime when the period's run began
     * @param scheduled when the schedule had it due (the clock's nanoTime)
     */
    public Snapshot tick(long start, long scheduled) {
        timing.started(start, scheduled);
        double t = (start - t0) * 1e-9;
        // a fresh joystick twist is written first: it needs no estimate, and waiting for the encoder read would add
        // that read's wire time to its latency
        boolean wroteTwist = mode == Mode.TELEOP && teleopSent != null && writeTwist(t);
        boolean sensorPeriod = sensors.isSensorPeriod();
        if (!sensorPeriod) {
            sensors.readEncoders();
        }
        pose = localizer.pose(t);
        velocity = localizer.velocity();
        if (mode != Mode.FAULT) {
            String unsafe = safetyCheck(t);
            if (unsafe != null) {
                fault(unsafe);
            }
        }
        if (!readyReported && !localizer.isSettling(t)) {
            readyReported = true;
            LOG.info("ready to move ({})", settings.localizer().useImu() ? "inertial biases settled after "
                    + settings.localizer().imuSettleTime() + " s at rest" : "odometry only");
        }
        // While a joystick drives, the sensor read comes before the wheel write: a twist that arrives during it then
        // goes out with this period's write, not in the next period (the read would otherwise end the period).
        boolean readFirst = sensorPeriod && mode == Mode.TELEOP && !wroteTwist;
        if (readFirst) {
            optionalReads(t, true);
        }
        if (mode == Mode.TELEOP && !wroteTwist) {
            // a twist that arrived during this period's encoder or sensor read goes out with this period's wheel
            // write, not at the start of the next period
            host.applyPendingCommands();
        }
        peers.refresh(clock.now(), settings.robotRadius());
        // every command passes the collision guard, whatever produced it
        Twist2D command = guard.limit(pose, command(t));
        if (mode == Mode.SETTLE || mode == Mode.WAIT) {
            passages.lapse(pose, settings.robotRadius()); // on a target: a claim ends once out of the passage
        }
        Twist2D applied = wroteTwist ? smoother.lastOutput() : smoother.smooth(t, command);
        if (!applied.isFinite()) {
            applied = Twist2D.ZERO;
        }
        if (tracker != null) {
            tracker.commandApplied(applied);
        }
        if (mode != Mode.FAULT && !wroteTwist) {
            WheelSpeeds w = drive.toWheelSpeeds(applied);
            try {
                boards.writeWheelSpeeds(w.left(), w.right());
                if (mode == Mode.TELEOP && teleopSent != null) {
                    teleopWritten();
                }
            } catch (RobotBoards.MotorFaultException e) {
                fault(e.getMessage());
            } catch (IOException e) {
                LOG.warn("wheel speed write failed: {}", e.getMessage());
            }
        }
        if (sensorPeriod && !readFirst) {
            optionalReads(t, false);
        }
        timing.ended(clock.nanoTime());
        if (settings.statusPeriod() > 0 && t - lastStatus >= settings.statusPeriod()) {
            lastStatus = t;
            STATUS.info("status pose x={} y={} theta={} v={} | mission {} {}% {}| mode {}{}", fmt(pose.x()),
                    fmt(pose.y()), fmt(pose.theta()), f2(velocity[0]), missions.status().state().name().toLowerCase(
                    Locale.ROOT), Math.round(missions.status().progress()), missions.status().detail().isBlank() ? ""
                            : "(" + missions.status().detail() + ") ",
                    mode.name().toLowerCase(Locale.ROOT), guard.status().isEmpty() ? "" : " | " + guard.status());
        }
        return snapshot();
    }

    /** @return why the robot must stop now, or null */
    private String safetyCheck(double t) {
        String board = boards.faultedBoard();
        if (board != null) {
            return "the " + board + " board does not answer";
        }
        if (localizer.isStale(t)) {
            // odometry goes stale before the bus calls the motor board faulted (its encoders are read every other
            // period): name the board when it is the reason
            double timeout = settings.localizer().odometryTimeout();
            return boards.motorBoardSilentFor(timeout / 2) ? "the sact board does not answer (no odometry for "
                    + timeout + " s)" : "no odometry for " + timeout + " s";
        }
        double sigma = localizer.positionSigma();
        if (sigma > settings.localizer().maxPositionSigma()) {
            return String.format(Locale.ROOT, "position uncertainty %.2f m above the limit %.2f m", sigma,
                    settings.localizer().maxPositionSigma());
        }
        return null;
    }

    /**
     * Reads the inertial board, one sonar sensor or the landmark board when the rest of the period leaves the time for
     * it (in the periods without an encoder read), in every mode: the collision guard needs fresh echoes most when a
     * joystick drives. While one does, the read comes before the period's wheel write ({@code writeFollows}), so that
     * a twist arriving during it goes out with that write.
     */
    private void optionalReads(double t, boolean writeFollows) {
        // the period's last transaction has just ended: the whole inter-frame silence comes first; when the wheel
        // write follows in this period, it must fit as well
        double silence = boards.interFrameDelay();
        double wire = boards.optionalReadWireTime() + (writeFollows ? silence + boards.wheelWriteWireTime() : 0);
        if (!fitsBeforeNextPeriod(silence, wire)) {
            timing.skippedOptionalRead();
            return;
        }
        try {
            sensors.readSpareSlot(t, pose);
        } catch (IOException e) {
            LOG.debug("optional read failed: {}", e.getMessage());
        }
        echoes.prune(t, settings.obstacleMemory());
    }

    /** @return how many landmark sightings the estimate used, for the log */
    public String landmarkSummary() {
        if (!localizer.usesLandmarks()) {
            return "no landmarks on the map";
        }
        long[] n = localizer.landmarkCounts();
        return "landmark fixes " + n[0] + " (" + n[1] + " rejected by the gate)";
    }

    // -------------------------------------------------------------------------------------------------- modes

    private Twist2D command(double t) {
        if (localizer.isSettling(t) && mode != Mode.IDLE && mode != Mode.FAULT) {
            if (!settlingReported) {
                settlingReported = true;
                LOG.info("holding still for {} s after the start while the inertial biases settle",
                        settings.localizer().imuSettleTime());
            }
            if (mode == Mode.FOLLOW) {
                trajectoryStart = t; // the trajectory starts when the robot may move
            }
            return Twist2D.ZERO;
        }
        switch (mode) {
            case TELEOP -> {
                // a joystick twist older than the deadman stops the robot; without the teleop task, at once
                double timeout = settings.joystick() ? settings.deadman() : 0;
                if (t - teleopTime > timeout) {
                    LOG.warn("joystick silent for more than {} s: stopping (deadman)", timeout);
                    brake();
                    setMode(Mode.IDLE, t);
                    return Twist2D.ZERO;
                }
                return teleopTwist;
            }
            case ALIGN -> {
                double target = trajectory.startPose().theta();
                double error = Pose2D.normalizeAngle(target - pose.theta());
                if (Math.abs(error) < ALIGNED && Math.abs(velocity[1]) < ALIGNED_RATE) {
                    startFollowing(t);
                    return follow(t);
                }
                return new Twist2D(0, turn.rate(error));
            }
            case FOLLOW -> {
                return follow(t);
            }
            case SETTLE -> {
                return settle(t);
            }
            case WAIT -> {
                if (!Double.isNaN(waitUntil) && t >= waitUntil) {
                    waitUntil = Double.NaN;
                    targetReached(t);
                }
                return Twist2D.ZERO;
            }
            case YIELD -> {
                return yieldAtPassage(t);
            }
            case BLOCKED -> {
                if (!replanPending && t - lastReplan >= REPLAN_RETRY) {
                    replan(t);
                }
                if (t - modeSince > settings.blockedTimeout()) {
                    fail("path blocked for " + settings.blockedTimeout() + " s");
                }
                return Twist2D.ZERO;
            }
            default -> {
                return Twist2D.ZERO;
            }
        }
    }

    private Twist2D follow(double t) {
        // A goal applied at the start of a period (the host applies queued commands first) starts its trajectory at
        // now(), a little after the period's clock t was read: that period samples the trajectory's start, not a time
        // before it.
        double tau = Math.max(0, t - trajectoryStart);
        if (tau >= trajectory.duration()) {
            setMode(Mode.SETTLE, t);
            positionSettled = false;
            stabilizer.reset();
            return settle(t);
        }
        PassageRule.Verdict passage = passageVerdict(tau);
        if (passage.kind() == PassageRule.Kind.YIELD) {
            LOG.info("yielding at {}: {}", PassageRule.describe(passage.passage()), passage.reason());
            yieldTau = tau;
            yieldReason = passage.reason();
            setMode(Mode.YIELD, t);
            return Twist2D.ZERO;
        }
        if (echoes.blocks(trajectory, tau, settings.blockedLookahead(), settings.robotRadius()
                + settings.blockedClearance())) {
            LOG.info("obstacle on the path ahead: stopping to replan");
            setMode(Mode.BLOCKED, t);
            replan(t);
            return Twist2D.ZERO;
        }
        PeerField.Disc robot = peers.blocking(trajectory, tau, settings.blockedLookahead(), settings.robotRadius()
                + settings.blockedClearance());
        if (robot != null) {
            LOG.info("robot {} on the path ahead: stopping to replan", robot.jid());
            setMode(Mode.BLOCKED, t);
            replan(t);
            return Twist2D.ZERO;
        }
        if (!progressChecker.isMakingProgress(t, pose)) {
            LOG.info("no progress for {} s: replanning", settings.progressTime());
            progressChecker.reset();
            setMode(Mode.BLOCKED, t);
            replan(t);
            return Twist2D.ZERO;
        }
        passThrough();
        missions.progress(Math.min(99, missions.legProgress(tau / trajectory.duration())));
        TrajectorySample ref = trajectory.sample(tau);
        ControlCommand c = tracker.update(t, pose, shift(ref, t));
        return c.twist();
    }

    /** @return the passage rule's verdict on the path ahead from trajectory time {@code tau} */
    private PassageRule.Verdict passageVerdict(double tau) {
        if (passages.passages().isEmpty()) {
            return PassageRule.Verdict.NONE;
        }
        double radius = settings.robotRadius();
        Passage ahead = passages.ahead(pose, trajectory, tau, peerSettings.passageApproach(), radius);
        return passages.decide(clock.now(), self.get(), ahead, pose, radius, peers.robots(), peers.current(),
                peers.memory());
    }

    /**
     * Stands short of a passage until the rule gives the robot its turn, then plans again from where it stands (the
     * trajectory's clock went on meanwhile); fails after {@code motion.passageTimeout}.
     */
    private Twist2D yieldAtPassage(double t) {
        PassageRule.Verdict v = passageVerdict(yieldTau);
        if (v.kind() == PassageRule.Kind.GO || v.kind() == PassageRule.Kind.NONE) {
            LOG.info("{}: going on", v.passage() == null ? "no passage ahead any more" : "its turn at "
                    + PassageRule.describe(v.passage()));
            setMode(Mode.BLOCKED, t);
            replan(t);
        } else if (t - modeSince > peerSettings.passageTimeout()) { // still yielding, or asking again
            fail(String.format(Locale.ROOT, "waited %.0f s at %s: %s", peerSettings.passageTimeout(), PassageRule
                    .describe(v.passage()), v.reason()));
        } else if (!v.reason().equals(yieldReason)) {
            yieldReason = v.reason();
            LOG.info("still yielding at {}: {}", PassageRule.describe(v.passage()), v.reason());
        }
        return Twist2D.ZERO;
    }

    /**
     * Brings the robot onto the goal: the DFL point stabilizer while the position is outside its tolerance, then a turn
     * in place onto the goal's heading (as Nav2's rotation shim does; a unicycle's point stabilizer converges slowly
     * in heading once the position error is small).
     */
    private Twist2D settle(double t) {
        Pose2D target = goal == null ? trajectory.endPose() : goal.pose();
        double distance = Math.hypot(target.x() - pose.x(), target.y() - pose.y());
        double headingError = Pose2D.normalizeAngle(target.theta() - pose.theta());
        double positionTolerance = goal == null ? settings.goalTolerance() : goal.positionTolerance();
        double headingTolerance = goal == null ? Math.PI : Math.min(Math.PI, goal.headingTolerance());
        // at rest first: the checker latches the position once within tolerance, and a robot passing through the
        // tolerance at speed must not have it latched (it would then be done wherever it comes to rest)
        if (Math.abs(velocity[0]) < 0.05 && Math.abs(velocity[1]) < 0.1 && goalChecker.isGoalReached(pose, target)) {
            brake();
            complete(t);
            return Twist2D.ZERO;
        }
        if (t - modeSince > settings.settleTimeout()) {
            fail(String.format(Locale.ROOT, "did not settle on the goal within %.0f s (%.2f m, %.2f rad away)",
                    settings.settleTimeout(), distance, headingError));
            return Twist2D.ZERO;
        }
        if (distance > positionTolerance * SETTLE_POSITION_FRACTION && !positionSettled) {
            ControlCommand c = stabilizer.update(t, pose, TrajectorySample.stationary(t, target));
            return c.twist();
        }
        positionSettled = true;
        if (Math.abs(headingError) <= headingTolerance * SETTLE_HEADING_FRACTION) {
            return Twist2D.ZERO;
        }
        return new Twist2D(0, turn.rate(headingError));
    }

    /** The controllers run on the loop clock: a reference sample at trajectory time tau is re-stamped at t. */
    private static TrajectorySample shift(TrajectorySample s, double t) {
        return new TrajectorySample(t, s.x(), s.y(), s.theta(), s.linearVelocity(), s.angularVelocity(), s.xDot(),
                s.yDot(), s.xDdot(), s.yDdot());
    }

    private void replan(double t) {
        lastReplan = t;
        if (goal == null) {
            fail("the imposed trajectory is blocked");
            return;
        }
        replanPending = true;
        host.planRequested(new LoopHost.PlanRequest(pose, via(), goal, echoes.points()));
    }

    /** @return the pass targets the robot still drives through before the leg's goal (none without a mission) */
    private List<Goal> via() {
        return missions.onTarget() ? missions.run().via() : List.of();
    }

    /** The plan asked for with {@code request} (ignored when the mission has moved on meanwhile). */
    public void replanned(LoopHost.PlanRequest request, Plan plan) {
        if (legPlanFor != null && request.goal() == legPlanFor) {
            legPlanFor = null;
            if (missions.status().state() != MissionState.RUNNING || request.goal() != goal) {
                return; // paused, aborted or replaced meanwhile: a resume plans again
            }
            if (plan.refusal() != null) {
                fail(missions.run().label() + ": " + plan.refusal());
                return;
            }
            LOG.info("{}: path {} m", missions.run().label(), fmt(plan.length()));
            clearFault(); // a target the robot stopped on braked it
            drive(plan, now());
            return;
        }
        replanPending = false;
        if (mode != Mode.BLOCKED || request.goal() != goal) {
            return;
        }
        if (plan.refusal() != null) {
            LOG.info("no path yet: {}", plan.refusal());
            return;
        }
        LOG.info("replanned around the obstacle: {} m", fmt(plan.length()));
        drive(plan, now()); // a robot already on the goal (paused there, then resumed) settles
    }

    // ----------------------------------------------------------------------------------------------- commands

    /**
     * Plans from {@code from} to the goal around {@code obstacles}; thread-safe (the planner serialises requests).
     */
    public Plan planPath(Pose2D from, Goal goal, List<Point2D> obstacles) {
        return planPath(from, List.of(), goal, obstacles);
    }

    /**
     * Plans from {@code from} through the {@code via} points (in order, as Nav2's NavigateThroughPoses) to the goal
     * around {@code obstacles}: one trajectory, so that the robot drives through each via point without stopping.
     * Thread-safe (the planner serialises requests).
     */
    public Plan planPath(Pose2D from, List<Goal> via, Goal goal, List<Point2D> obstacles) {
        List<List<Point2D>> segments = new java.util.ArrayList<>();
        List<Point2D> ends = new java.util.ArrayList<>();
        Point2D start = from.position();
        LoopSettings s = settings;
        List<PeerField.Disc> discs = peers.discs(clock.now(), s.robotRadius());
        List<MovingObstacle> robots = PeerField.obstacles(discs);
        List<Point2D> echoes = PeerField.unexplained(obstacles, discs);
        for (Goal g : concat(via, goal)) {
            PlanResult result = planner.plan(start, g.pose().position(), echoes, robots);
            if (result instanceof PlanResult.Unreachable u) {
                return new Plan(null, 0, "unreachable goal: " + u.detail());
            }
            segments.add(((PlanResult.Found) result).path().waypoints());
            ends.add(g.pose().position());
            start = g.pose().position();
        }
        return TrajectoryFitter.fit(segments, from.position(), ends, limits.withHeadroom(s.speedHeadroom(),
                s.accelerationHeadroom()));
    }

    private static List<Goal> concat(List<Goal> via, Goal goal) {
        List<Goal> all = new java.util.ArrayList<>(via);
        all.add(goal);
        return all;
    }

    /** Starts a mission to one goal with its first plan; replaces a running mission (the queue stays). */
    public void startMission(Goal g, Plan plan) {
        missions.single();
        startLeg(g, plan, "to (" + fmt(g.pose().x()) + ", " + fmt(g.pose().y()) + ")");
    }

    /**
     * Starts a mission of targets; replaces a running mission (the queue stays). The robot stands until its first leg
     * is planned (within a period or two).
     *
     * @param targets the targets in order, at least one
     */
    public void startMission(List<MissionTarget> targets) {
        startRun(List.copyOf(targets), now());
        LOG.info("mission of {} targets started", targets.size());
    }

    /**
     * Queues a mission of targets after the running one and those queued before; when no mission runs it starts at
     * once (its first leg planned from where the robot stands then).
     *
     * @return false when the queue is full ({@link MissionStatus#MAX_QUEUED}): nothing changed
     */
    public boolean enqueue(List<MissionTarget> targets) {
        if (missions.status().state().isActive()) {
            if (!missions.enqueue(targets)) {
                return false;
            }
            LOG.info("mission of {} targets queued ({} waiting)", targets.size(), missions.queued());
            return true;
        }
        startRun(List.copyOf(targets), now());
        LOG.info("mission of {} targets started from the queue", targets.size());
        return true;
    }

    /** @return the missions waiting in the queue */
    public int queued() {
        return missions.queued();
    }

    private void startRun(List<MissionTarget> targets, double t) {
        clearFault();
        missions.start(targets);
        waitUntil = Double.NaN;
        trajectory = null;
        trajectoryPayload = new TrajectoryPayload(clock.now(), List.of());
        setMode(Mode.WAIT, t);
        requestLeg(t);
    }

    private void startLeg(Goal g, Plan plan, String detail) {
        double t = now();
        clearFault();
        this.goal = g;
        legPlanFor = null;
        waitUntil = Double.NaN;
        goalChecker = checkerFor(g);
        missions.report(MissionState.RUNNING, missions.legProgress(0), detail);
        drive(plan, t);
    }

    /** Follows the plan's trajectory; without one (the robot stands on the goal's position) settles on the goal. */
    private void drive(Plan plan, double t) {
        if (plan.trajectory() == null) {
            trajectory = null;
            trajectoryPayload = new TrajectoryPayload(clock.now(), List.of());
            stabilizer.reset();
            positionSettled = false;
            setMode(Mode.SETTLE, t);
            return;
        }
        setTrajectory(plan, t);
    }

    public void followImposed(TrajectoryPayload imposed) {
        double t = now();
        clearFault();
        this.goal = null;
        missions.single();
        legPlanFor = null;
        waitUntil = Double.NaN;
        Trajectory path = new SampledTrajectory(imposed.points());
        goalChecker = new GoalChecker(settings.goalTolerance(), Math.PI, true);
        missions.report(MissionState.RUNNING, 0, "imposed trajectory");
        setTrajectory(new Plan(path, path.length(), null), t);
    }

    private void setTrajectory(Plan plan, double t) {
        trajectory = plan.trajectory();
        trajectoryPayload = new TrajectoryPayload(clock.now(), SampledTrajectory.points(trajectory));
        progressChecker = new ProgressChecker(settings.progressRadius(), settings.progressTime());
        double error = Pose2D.normalizeAngle(trajectory.startPose().theta() - pose.theta());
        if (Math.abs(error) > ALIGN_THRESHOLD) {
            setMode(Mode.ALIGN, t);
        } else {
            startFollowing(t);
        }
    }

    private void startFollowing(double t) {
        trajectoryStart = t;
        tracker.reset();
        progressChecker.reset();
        setMode(Mode.FOLLOW, t);
    }

    /**
     * A joystick twist.
     *
     * @param receivedNanos when it was received (the clock's nanoTime): the deadman is judged on it
     * @param sent          when the operator sent it (wall clock), for the latency
     */
    public void teleop(Twist2D twist, long receivedNanos, Instant sent) {
        double t = (receivedNanos - t0) * 1e-9;
        teleopSent = sent;
        clearFault();
        if (mode != Mode.TELEOP && mode != Mode.IDLE) {
            return;
        }
        teleopTwist = twist;
        teleopTime = t;
        if (mode != Mode.TELEOP) {
            setMode(Mode.TELEOP, now());
        }
    }

    /**
     * Writes the newest joystick twist at once when the bus is free long enough before the next period (a twist would
     * otherwise wait up to a period for its write); the period's own work is never delayed by it.
     */
    public void teleopWrite() {
        if (mode != Mode.TELEOP || teleopSent == null) {
            return;
        }
        // the silence after the period's last answer has partly or wholly passed while the twist was on its way
        double sinceWork = (clock.nanoTime() - timing.lastEndNanos()) * 1e-9;
        if (fitsBeforeNextPeriod(Math.max(0, boards.interFrameDelay() - sinceWork), boards.wheelWriteWireTime())) {
            writeTwist(now());
        }
    }

    /**
     * Whether a transaction ends before the next period is due: the bus's silence still to keep before the request,
     * the wire time with {@link #WIRE_TIME_FACTOR} for the slave's turnaround, and {@link #PERIOD_MARGIN}. Measured
     * against the next period's scheduled start, not this one's actual start, so that a period that began late drops
     * its optional work and the schedule catches up.
     *
     * @param silence  seconds of inter-frame silence still due before the request may be sent
     * @param wireTime the transaction's computed wire time, seconds
     */
    private boolean fitsBeforeNextPeriod(double silence, double wireTime) {
        double left = (timing.nextStartNanos() - clock.nanoTime()) * 1e-9;
        return left >= silence + wireTime * WIRE_TIME_FACTOR + PERIOD_MARGIN;
    }

    /** The newest joystick twist has reached the board (through the smoother): its latency is recorded. */
    private void teleopWritten() {
        teleopLatency.add(Duration.between(teleopSent, clock.now()).toNanos());
        teleopSent = null;
    }

    /** Writes the joystick's twist through the smoother; records its latency. @return true when written */
    private boolean writeTwist(double t) {
        Twist2D applied = smoother.smooth(t, guard.limit(pose, teleopTwist));
        WheelSpeeds w = drive.toWheelSpeeds(applied.isFinite() ? applied : Twist2D.ZERO);
        try {
            boards.writeWheelSpeeds(w.left(), w.right());
            teleopWritten();
            return true;
        } catch (RobotBoards.MotorFaultException e) {
            teleopSent = null;
            fault(e.getMessage());
            return false;
        } catch (IOException e) {
            LOG.debug("joystick write failed: {}", e.getMessage());
            return false;
        }
    }

    public void relocalise(Pose2D p) {
        localizer.reset(p, now());
        LOG.info("re-localised at {}", p);
    }

    public void limitsChanged(MotionLimits l) {
        this.limits = l;
        guard.configure(settings, l);
        smoother = new VelocitySmoother(l, settings.deadman());
        tracker = controllers.tracker(l);
        stabilizer = controllers.stabilizer(l);
        turn = new TurnInPlace(l.maxAngularSpeed() * TURN_FRACTION, l.maxAngularAcceleration() * TURN_FRACTION,
                TURN_GAIN);
        try {
            // the fastest wheel under these limits: full speed while turning at the full yaw rate
            double wheel = Math.min(l.maxWheelRimSpeed(), l.maxLinearSpeed() + l.maxAngularSpeed() * l.trackWidth() / 2);
            boards.writeLimits(wheel, l.maxLinearAcceleration());
        } catch (IOException | RuntimeException e) {
            LOG.debug("board limits not written: {}", e.getMessage());
        }
    }

    public void pause() {
        if (missions.status().state() != MissionState.RUNNING) {
            return;
        }
        pausedFrom = mode;
        double t = now();
        if (!Double.isNaN(waitUntil)) {
            waitLeft = Math.max(0, waitUntil - t);
            waitUntil = Double.NaN;
        }
        setMode(Mode.PAUSED, t);
        missions.report(MissionState.PAUSED, missions.status().progress(), "paused");
    }

    public void resume() {
        if (mode != Mode.PAUSED) {
            return;
        }
        double t = now();
        clearFault(); // a robot paused on a target it stopped on is braked
        missions.report(MissionState.RUNNING, missions.status().progress(), "resumed");
        if (pausedFrom == Mode.WAIT && waitLeft > 0) {
            // the rest of a target's wait
            waitUntil = t + waitLeft;
            waitLeft = 0;
            setMode(Mode.WAIT, t);
        } else if (pausedFrom == Mode.FOLLOW || pausedFrom == Mode.ALIGN || pausedFrom == Mode.BLOCKED
                || pausedFrom == Mode.WAIT) {
            // the trajectory's clock went on while paused: plan again from where the robot stands
            setMode(Mode.BLOCKED, t);
            replan(t);
        } else {
            setMode(pausedFrom, t);
        }
    }

    public void abort(String reason) {
        double t = now();
        brake();
        MissionState state = missions.status().state();
        if (state == MissionState.RUNNING || state == MissionState.PAUSED) {
            endRun();
            missions.report(MissionState.ABORTED, missions.status().progress(), reason + missions.dropQueue());
        }
        setMode(Mode.IDLE, t);
        LOG.info("stopped: {}", reason);
    }

    /** @return why the PID step test of {@code motor} by {@code step} m may not start from here, or null */
    public String stepTestBlocked(int motor, double step) {
        return guard.stepBlocked(pose, drive, motor, step);
    }

    public void maintenance(boolean on, String detail) {
        brake();
        MissionState state = missions.status().state();
        String dropped = "";
        if (on && (state == MissionState.RUNNING || state == MissionState.PAUSED)) {
            state = MissionState.ABORTED;
            endRun();
            dropped = missions.dropQueue();
            LOG.info("mission aborted for maintenance");
        }
        setMode(Mode.IDLE, now());
        missions.report(state, on, missions.status().progress(), (on ? (detail == null || detail.isBlank()
                ? "maintenance" : detail) : "maintenance ended") + dropped);
        LOG.info("maintenance {}", on ? "on" : "off");
    }

    /** Brakes and marks the mission failed with the reason; the robot stays still until a new command. */
    public void fault(String reason) {
        if (mode == Mode.FAULT && reason.equals(missions.status().detail())) {
            return;
        }
        LOG.warn("fault: {} - braking", reason);
        brake();
        setMode(Mode.FAULT, now());
        String dropped = "";
        if (missions.status().state().isActive()) {
            endRun();
            dropped = missions.dropQueue();
        }
        missions.report(MissionState.FAILED, missions.status().progress(), reason + dropped);
    }

    /** Releases the brake (after a stop or a fault) so that a new command can move the robot. */
    private void clearFault() {
        if (braked) {
            try {
                boards.acknowledgeFaults();
                boards.brake(false);
                braked = false;
            } catch (IOException e) {
                LOG.warn("could not release the brake: {}", e.getMessage());
            }
            resetSmoother();
        }
        if (mode == Mode.FAULT) {
            setMode(Mode.IDLE, now());
        }
    }

    /** Starts the smoother from rest (with the deadman in force now). */
    private void resetSmoother() {
        smoother = new VelocitySmoother(limits, settings.deadman());
    }

    private void brake() {
        resetSmoother();
        try {
            boards.brake(true);
            braked = true;
        } catch (IOException e) {
            LOG.warn("brake command failed ({}); the motor board's own deadman stops the wheels", e.getMessage());
            braked = true;
        }
    }

    private void complete(double t) {
        MissionRun run = missions.run();
        if (missions.onTarget()) {
            if (run.passing()) {
                // the trajectory went through a pass target outside its tolerance: the mission says so
                Goal missed = run.target().goal();
                fail(String.format(Locale.ROOT, "%s (pass) missed by %.2f m", run.label(), Math.hypot(missed.pose()
                        .x() - pose.x(), missed.pose().y() - pose.y())));
                return;
            }
            MissionTarget target = run.target();
            LOG.info("{} reached at ({}, {}, {})", run.label(), fmt(pose.x()), fmt(pose.y()), fmt(pose.theta()));
            if (target.action() == MissionTarget.Action.WAIT) {
                waitUntil = t + target.dwell();
                setMode(Mode.WAIT, t);
                missions.report(MissionState.RUNNING, run.progress(1), "waiting " + fmtWait(target.dwell())
                        + " s at " + run.label());
                return;
            }
            targetReached(t);
            return;
        }
        missions.report(MissionState.DONE, 100, "goal reached");
        setMode(Mode.IDLE, t);
        LOG.info("goal reached at ({}, {}, {})", fmt(pose.x()), fmt(pose.y()), fmt(pose.theta()));
        startNextQueued(t);
    }

    /** The current target is done (reached, and its wait over): on to the next, or the mission is done. */
    private void targetReached(double t) {
        MissionRun run = missions.run();
        boolean docked = run.target().action() == MissionTarget.Action.DOCK;
        run.reached();
        if (run.hasCurrent()) {
            requestLeg(t);
            return;
        }
        trajectory = null;
        setMode(Mode.IDLE, t);
        missions.report(MissionState.DONE, 100, "all " + run.size() + " targets reached" + (docked ? ", docked"
                : ""));
        LOG.info("mission done: all {} targets reached", run.size());
        startNextQueued(t);
    }

    /**
     * Asks for the plan of the next leg, from where the robot stands now through the pass targets ahead to the next
     * target it stops on; the robot stands until the plan comes (within a period or two).
     */
    private void requestLeg(double t) {
        MissionRun run = missions.run();
        run.legStarted();
        goal = run.legGoal();
        goalChecker = checkerFor(goal);
        legPlanFor = goal;
        setMode(Mode.WAIT, t);
        missions.report(MissionState.RUNNING, run.progress(0), legDetail());
        host.planRequested(new LoopHost.PlanRequest(pose, via(), goal, echoes.points()));
    }

    /** A pass target the leg's trajectory goes through is reached once the robot is within its tolerance. */
    private void passThrough() {
        MissionRun run = missions.run();
        if (run == null || !run.passing()) {
            return;
        }
        Goal pass = run.target().goal();
        if (Math.hypot(pass.pose().x() - pose.x(), pass.pose().y() - pose.y()) <= pass.positionTolerance()) {
            LOG.info("{} passed at ({}, {})", run.label(), fmt(pose.x()), fmt(pose.y()));
            run.reached();
            missions.report(MissionState.RUNNING, missions.status().progress(), legDetail());
        }
    }

    private String legDetail() {
        MissionRun run = missions.run();
        Pose2D p = run.hasCurrent() ? run.target().goal().pose() : run.legGoal().pose();
        return run.label() + ": to (" + fmt(p.x()) + ", " + fmt(p.y()) + ")";
    }

    private static GoalChecker checkerFor(Goal g) {
        return new GoalChecker(g.positionTolerance(), Math.min(Math.PI, g.headingTolerance()), true);
    }

    private static String fmtWait(double s) {
        return s == Math.rint(s) ? String.valueOf((long) s) : String.format(Locale.ROOT, "%.1f", s);
    }

    /** After a mission is done, the next queued one starts. */
    private void startNextQueued(double t) {
        List<MissionTarget> next = missions.nextQueued();
        if (next != null) {
            startRun(next, t);
            LOG.info("mission of {} targets started from the queue", next.size());
        }
    }

    /** The mission ends short of its targets (failed or aborted): its current target failed, no leg awaited. */
    private void endRun() {
        missions.endShort();
        legPlanFor = null;
        waitUntil = Double.NaN;
        waitLeft = 0;
    }

    private void fail(String reason) {
        brake();
        endRun();
        missions.report(MissionState.FAILED, missions.status().progress(), reason + missions.dropQueue());
        setMode(Mode.IDLE, now());
        LOG.warn("mission failed: {}", reason);
    }

    private void setMode(Mode m, double t) {
        if (m != mode) {
            LOG.debug("mode {} -> {}", mode, m);
        }
        mode = m;
        modeSince = t;
        if (m == Mode.IDLE || m == Mode.PAUSED || m == Mode.FAULT || m == Mode.TELEOP) {
            passages.release(); // no mission drives on: its claim ends (a robot standing in a passage is in it)
        }
    }

    // ----------------------------------------------------------------------------------------------- snapshot

    /** @return the loop's state now, stamped with the clock's wall time */
    public Snapshot snapshot() {
        Instant now = clock.now();
        double[][] c = localizer.covariance();
        PoseEstimate p = new PoseEstimate(now, pose, new PoseCovariance(c[0][0], c[0][1], c[0][2], c[1][1], c[1][2],
                c[2][2]));
        VelocityCommand v = new VelocityCommand(now, new Twist2D(velocity[0], velocity[1]));
        boolean moving = mode == Mode.TELEOP || mode == Mode.ALIGN || mode == Mode.FOLLOW || mode == Mode.SETTLE
                || Math.abs(velocity[0]) > 0.02 || Math.abs(velocity[1]) > 0.05;
        return new Snapshot(p, v, withGuardStatus(missions.status()), Optional.ofNullable(goal), trajectoryPayload,
                new Obstacles(now, echoes.obstacles()), moving, timing.summary(), mode, sensors.battery(),
                sensors.batteryFault(), Optional.ofNullable(passages.claim()));
    }

    /**
     * @return the mission as reported: while the collision guard limits the robot, its words are the detail (a joystick
     *         drives) or follow it (a mission runs), so that the operator reads why the robot slows or stands; so do
     *         a yield's at a passage ({@code yielding at passage 1: sabot-02@sabot.local passes})
     */
    private MissionStatus withGuardStatus(MissionStatus m) {
        String g = guard.status();
        if (mode == Mode.YIELD) {
            String y = "yielding at passage " + (passages.claim() == null ? "" : passages.claim().passage() + "")
                    + ": " + yieldReason;
            g = g.isEmpty() ? y : y + "; " + g;
        }
        if (g.isEmpty()) {
            return m;
        }
        String detail = mode == Mode.TELEOP || m.detail().isBlank() ? g : m.detail() + "; " + g;
        return m.with(m.state(), m.progress(), detail);
    }

    /** @return {@code v} with three decimals, for the log */
    public static String fmt(double v) {
        return String.format(Locale.ROOT, "%.3f", v);
    }

    private static String f2(double v) {
        return String.format(Locale.ROOT, "%.2f", v);
    }
}
