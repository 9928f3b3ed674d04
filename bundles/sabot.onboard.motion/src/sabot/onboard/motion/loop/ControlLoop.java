package sabot.onboard.motion.internal;

import java.io.IOException;
import java.time.Instant;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Deque;
import java.util.HashSet;
import java.util.List;
import java.util.Locale;
import java.util.Optional;
import java.util.Set;

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
import sabot.control.trajectory.InvalidPathException;
import sabot.control.trajectory.SplineTrajectory;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.Obstacle;
import sabot.controlml.payload.Obstacles;
import sabot.controlml.payload.PoseEstimate;
import sabot.controlml.payload.TrajectoryPayload;
import sabot.controlml.payload.VelocityCommand;
import sabot.localization.MeasurementResult;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.path.Trajectory;
import sabot.model.path.TrajectorySample;
import sabot.model.robot.RobotDescription;
import sabot.planner.PlanResult;

/**
 * The control loop's state and one period of it. Every method runs on the loop's thread, except {@link #planPath},
 * which only reads immutable inputs and the planner (serialised by itself).
 */
final class ControlLoop {

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
    /** Spacing of the waypoints the spline is fitted through, m (planner paths come cell by cell). */
    static final double WAYPOINT_SPACING = 0.3;
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
    /** One optional read in this many goes to the landmark board (about 6 Hz at 50 Hz; the board measures at 10). */
    static final int LANDMARK_SLOTS = 8;
    /** Seconds between two reads of a landmark board that has stopped answering. */
    static final double LANDMARK_RETRY = 2.0;
    /** Half-angle of a sonar's beam (HC-SR04 figures, onboard-bridge/README.md): an echo lies within it. */
    static final double SONAR_HALF_BEAM = Math.toRadians(15);
    /** Largest number of obstacle points kept (cm.obstacles allows 1024 rows). */
    static final int MAX_OBSTACLES = 1024;
    /** Reported radius of one sonar obstacle point, m (one echo: the sonar's resolution, not the object's size). */
    static final double ECHO_RADIUS = 0.05;

    /** What the loop is doing. */
    enum Mode {
        IDLE, TELEOP, ALIGN, FOLLOW, SETTLE, BLOCKED, PAUSED, FAULT
    }

    /** A planned path turned into a trajectory, or why not. */
    record Plan(Trajectory trajectory, double length, String refusal) {
    }

    private final MotionTask owner;
    private final MotionTask.Config config;
    private final RobotBoards boards;
    private final DifferentialDrive drive;
    private final Localizer localizer;
    private final LocalizerTask localizerTask;
    private final PlannerTask plannerTask;
    private final TrackerTask trackerTask;
    private final long t0 = System.nanoTime();
    private final LoopTiming timing;
    private final Deque<double[]> echoes = new ArrayDeque<>();

    private MotionLimits limits;
    private VelocitySmoother smoother;
    private TrackingController tracker;
    private TrackingController stabilizer;
    private TurnInPlace turn;
    private GoalChecker goalChecker;
    private ProgressChecker progressChecker;

    private Mode mode = Mode.IDLE;
    private Mode pausedFrom;
    private MissionStatus mission = new MissionStatus(MissionState.IDLE, false, 0, "idle");
    private Goal goal;
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
    private int optionalRound;
    /** Periods since the start: the even ones read the encoders, the odd ones a sensor board (outside teleop). */
    private long periodCount;
    private int lastLandmarkSequence = -1;
    private double lastLandmarkTry = Double.NEGATIVE_INFINITY;
    private final Set<Integer> unknownLandmarks = new HashSet<>();
    private int sonarRound;
    private double lastStatus = Double.NEGATIVE_INFINITY;
    private Pose2D pose;
    private double[] velocity = { 0, 0 };

    ControlLoop(MotionTask owner, MotionTask.Config config, RobotBoards boards, RobotDescription robot,
            LocalizerTask localizerTask, PlannerTask plannerTask, TrackerTask trackerTask) {
        this.owner = owner;
        this.config = config;
        this.boards = boards;
        this.drive = DifferentialDrive.of(robot);
        this.localizerTask = localizerTask;
        this.localizer = localizerTask.newLocalizer(plannerTask.landmarks());
        this.plannerTask = plannerTask;
        this.trackerTask = trackerTask;
        this.timing = new LoopTiming(Math.round(1e9 / config.rate()));
        this.pose = localizerTask.start();
        limitsChanged(owner.currentLimits());
    }

    private double now() {
        return (System.nanoTime() - t0) * 1e-9;
    }

    LoopTiming timing() {
        return timing;
    }

    /** @return joystick twist sent → wheel set-point written, as measured so far */
    MicrosHistogram teleopLatency() {
        return teleopLatency;
    }

    // --------------------------------------------------------------------------------------------- one period

    /**
     * One period of the loop.
     *
     * @param start     System.nanoTime when the period's run began
     * @param scheduled when the schedule had it due (System.nanoTime)
     */
    MotionTask.Snapshot tick(long start, long scheduled) {
        timing.started(start, scheduled);
        double t = (start - t0) * 1e-9;
        // a fresh joystick twist is written first: it needs no estimate, and waiting for the encoder read would add
        // that read's wire time to its latency
        boolean wroteTwist = mode == Mode.TELEOP && teleopSent != null && writeTwist(t);
        // The line carries two transactions per period with the margin the schedule needs (115200 baud: encoder
        // read 5.2 ms + wheel write 4.8 ms of wire time, each after a 1.75 ms silence), not three. So the encoders are
        // read every other period and a sensor board in the periods between (the encoder counts are cumulative: read
        // at 25 Hz they lose no distance; the estimate is predicted in between). While a joystick drives, the
        // encoders are read every period and no sensor board (its twists need the spare time).
        boolean sensorPeriod = mode != Mode.TELEOP && (periodCount++ & 1) == 1;
        if (!sensorPeriod) {
            readEncoders();
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
            LOG.info("ready to move ({})", localizerTask.config().useImu() ? "inertial biases settled after "
                    + localizerTask.config().imuSettleTime() + " s at rest" : "odometry only");
        }
        if (mode == Mode.TELEOP && !wroteTwist) {
            // a twist that arrived during this period's encoder read goes out with this period's wheel write, not at
            // the start of the next period
            owner.applyCommands();
        }
        Twist2D command = command(t);
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
        if (sensorPeriod) {
            optionalReads(t);
        }
        timing.ended(System.nanoTime());
        if (config.statusPeriod() > 0 && t - lastStatus >= config.statusPeriod()) {
            lastStatus = t;
            STATUS.info("status pose x={} y={} theta={} v={} | mission {} {}% {}| mode {}", f3(pose.x()), f3(pose.y()),
                    f3(pose.theta()), f2(velocity[0]), mission.state().name().toLowerCase(Locale.ROOT),
                    Math.round(mission.progress()), mission.detail().isBlank() ? "" : "(" + mission.detail() + ") ",
                    mode.name().toLowerCase(Locale.ROOT));
        }
        return snapshot(Instant.now());
    }

    /** A failed read is not an error by itself: the localizer's odometry timeout and the bus's fault time judge. */
    private void readEncoders() {
        try {
            RobotBoards.WheelCounts c = boards.readEncoders();
            // stamped when the answer arrived, not when the period began: a retried read is tens of ms late, and
            // odometry's speed is distance over the time between two readings
            localizer.encoders(now(), c.left(), c.right());
        } catch (IOException e) {
            LOG.debug("encoder read failed: {}", e.getMessage());
        }
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
            double timeout = localizerTask.config().odometryTimeout();
            return boards.motorBoardSilentFor(timeout / 2) ? "the sact board does not answer (no odometry for "
                    + timeout + " s)" : "no odometry for " + timeout + " s";
        }
        double sigma = localizer.positionSigma();
        if (sigma > localizerTask.config().maxPositionSigma()) {
            return String.format(Locale.ROOT, "position uncertainty %.2f m above the limit %.2f m", sigma,
                    localizerTask.config().maxPositionSigma());
        }
        return null;
    }

    /**
     * Reads the inertial board, one sonar sensor or the landmark board when the rest of the period leaves the time for
     * it (in the periods without an encoder read). Not while a joystick drives: the spare bus time is kept for
     * writing its twists as they arrive (odometry alone estimates the pose meanwhile, and the sonar guards missions,
     * not teleop).
     */
    private void optionalReads(double t) {
        if (mode == Mode.TELEOP) {
            return;
        }
        // the period's last transaction has just ended: the whole inter-frame silence comes first
        if (!fitsBeforeNextPeriod(boards.interFrameDelay(), boards.optionalReadWireTime())) {
            timing.skippedOptionalRead();
            return;
        }
        int sonars = boards.sonarSensors();
        int round = optionalRound++;
        try {
            // every other spare slot goes to the gyro; one in eight to the landmark board (it measures at 10 Hz), the
            // others to the sonar sensors in turn
            if (round % LANDMARK_SLOTS == 1 && landmarkReadDue(t)) {
                readLandmark();
            } else if (round % 2 == 0 || sonars == 0) {
                RobotBoards.ImuSample s = boards.readImu();
                localizer.inertial(now(), s.yawRate(), s.forwardAcceleration());
            } else {
                int sensor = sonarRound++ % sonars;
                for (Point2D p : boards.readSonar(sensor)) {
                    addEcho(t, p);
                }
            }
        } catch (IOException e) {
            LOG.debug("optional read failed: {}", e.getMessage());
        }
        pruneEchoes(t);
    }

    /** @return how many landmark sightings the estimate used, for the log */
    String landmarkSummary() {
        if (!localizer.usesLandmarks()) {
            return "no landmarks on the map";
        }
        long[] n = localizer.landmarkCounts();
        return "landmark fixes " + n[0] + " (" + n[1] + " rejected by the gate)";
    }

    /** A landmark board that stopped answering is asked again only every {@link #LANDMARK_RETRY} s. */
    private boolean landmarkReadDue(double t) {
        if (!localizer.usesLandmarks()) {
            return false;
        }
        if (boards.landmarkBoardFaulted() && t - lastLandmarkTry < LANDMARK_RETRY) {
            return false;
        }
        lastLandmarkTry = t;
        return true;
    }

    private void readLandmark() throws IOException {
        RobotBoards.LandmarkSighting s = boards.readLandmark();
        if (s.sequence() == lastLandmarkSequence) {
            return; // read again before the board measured anew
        }
        lastLandmarkSequence = s.sequence();
        if (s.landmarkId() != 0) {
            MeasurementResult r = localizer.landmark(now(), s.landmarkId(), s.range(), s.bearing(), s.age());
            if (r == null && unknownLandmarks.add(s.landmarkId())) {
                LOG.warn("landmark {} seen but not on the map's landmark list: ignored", s.landmarkId());
            }
        }
    }

    private void addEcho(double t, Point2D robotFrame) {
        double c = Math.cos(pose.theta());
        double s = Math.sin(pose.theta());
        Point2D p = new Point2D(pose.x() + c * robotFrame.x() - s * robotFrame.y(),
                pose.y() + s * robotFrame.x() + c * robotFrame.y());
        // the board puts an echo on the beam's axis; the reflector may be anywhere across the beam at that range
        double across = Math.hypot(robotFrame.x(), robotFrame.y()) * Math.sin(SONAR_HALF_BEAM);
        if (plannerTask.planner().isNearStaticObstacle(p, across)) {
            return;
        }
        echoes.addLast(new double[] { t, p.x(), p.y() });
        while (echoes.size() > MAX_OBSTACLES) {
            echoes.removeFirst();
        }
    }

    private void pruneEchoes(double t) {
        while (!echoes.isEmpty() && t - echoes.peekFirst()[0] > config.obstacleMemory()) {
            echoes.removeFirst();
        }
    }

    private List<Point2D> echoPoints() {
        List<Point2D> points = new ArrayList<>(echoes.size());
        for (double[] e : echoes) {
            points.add(new Point2D(e[1], e[2]));
        }
        return points;
    }

    // -------------------------------------------------------------------------------------------------- modes

    private Twist2D command(double t) {
        if (localizer.isSettling(t) && mode != Mode.IDLE && mode != Mode.FAULT) {
            if (!settlingReported) {
                settlingReported = true;
                LOG.info("holding still for {} s after the start while the inertial biases settle",
                        localizerTask.config().imuSettleTime());
            }
            if (mode == Mode.FOLLOW) {
                trajectoryStart = t; // the trajectory starts when the robot may move
            }
            return Twist2D.ZERO;
        }
        switch (mode) {
            case TELEOP -> {
                TeleopTask teleop = owner.teleop();
                double timeout = teleop == null ? 0 : teleop.config().timeout();
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
            case BLOCKED -> {
                if (!replanPending && t - lastReplan >= REPLAN_RETRY) {
                    replan(t);
                }
                if (t - modeSince > plannerTask.config().blockedTimeout()) {
                    fail("path blocked for " + plannerTask.config().blockedTimeout() + " s");
                }
                return Twist2D.ZERO;
            }
            default -> {
                return Twist2D.ZERO;
            }
        }
    }

    private Twist2D follow(double t) {
        // A goal applied at the start of a period (MotionTask.tick) starts its trajectory at now(), a little after the
        // period's clock t was read: that period samples the trajectory's start, not a time before it.
        double tau = Math.max(0, t - trajectoryStart);
        if (tau >= trajectory.duration()) {
            setMode(Mode.SETTLE, t);
            positionSettled = false;
            stabilizer.reset();
            return settle(t);
        }
        if (blocked(tau)) {
            LOG.info("obstacle on the path ahead: stopping to replan");
            setMode(Mode.BLOCKED, t);
            replan(t);
            return Twist2D.ZERO;
        }
        if (!progressChecker.isMakingProgress(t, pose)) {
            LOG.info("no progress for {} s: replanning", trackerTask.config().progressTime());
            progressChecker.reset();
            setMode(Mode.BLOCKED, t);
            replan(t);
            return Twist2D.ZERO;
        }
        updateProgress(Math.min(99, 100 * tau / trajectory.duration()));
        TrajectorySample ref = trajectory.sample(tau);
        ControlCommand c = tracker.update(t, pose, shift(ref, t));
        return c.twist();
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
        double positionTolerance = goal == null ? config.goalTolerance() : goal.positionTolerance();
        double headingTolerance = goal == null ? Math.PI : Math.min(Math.PI, goal.headingTolerance());
        // at rest first: the checker latches the position once within tolerance, and a robot passing through the
        // tolerance at speed must not have it latched (it would then be done wherever it comes to rest)
        if (Math.abs(velocity[0]) < 0.05 && Math.abs(velocity[1]) < 0.1 && goalChecker.isGoalReached(pose, target)) {
            brake();
            complete(t);
            return Twist2D.ZERO;
        }
        if (t - modeSince > trackerTask.config().settleTimeout()) {
            fail(String.format(Locale.ROOT, "did not settle on the goal within %.0f s (%.2f m, %.2f rad away)",
                    trackerTask.config().settleTimeout(), distance, headingError));
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

    private boolean blocked(double tau) {
        if (echoes.isEmpty()) {
            return false;
        }
        double clearance = plannerTask.config().robotRadius() + config.blockedClearance();
        double end = Math.min(trajectory.duration(), tau + config.blockedLookahead());
        for (double s = tau; s <= end; s += 0.1) {
            TrajectorySample r = trajectory.sample(s);
            for (double[] e : echoes) {
                if (Math.hypot(e[1] - r.x(), e[2] - r.y()) < clearance) {
                    return true;
                }
            }
        }
        return false;
    }

    private void replan(double t) {
        lastReplan = t;
        if (goal == null) {
            fail("the imposed trajectory is blocked");
            return;
        }
        replanPending = true;
        Pose2D from = pose;
        Goal g = goal;
        List<Point2D> obstacles = echoPoints();
        owner.plan(() -> {
            Plan plan = planPath(from, g, obstacles);
            owner.enqueue(loop -> loop.replanned(g, plan));
        });
    }

    private void replanned(Goal g, Plan plan) {
        replanPending = false;
        if (mode != Mode.BLOCKED || g != goal) {
            return;
        }
        if (plan.refusal() != null) {
            LOG.info("no path yet: {}", plan.refusal());
            return;
        }
        LOG.info("replanned around the obstacle: {} m", MotionTask.fmt(plan.length()));
        setTrajectory(plan, now());
    }

    // ----------------------------------------------------------------------------------------------- commands

    /**
     * Plans from {@code from} to the goal around {@code obstacles}; thread-safe (the planner serialises requests).
     */
    Plan planPath(Pose2D from, Goal goal, List<Point2D> obstacles) {
        PlanResult result = plannerTask.planner().plan(from.position(), goal.pose().position(), obstacles);
        if (result instanceof PlanResult.Unreachable u) {
            return new Plan(null, 0, "unreachable goal: " + u.detail());
        }
        List<Point2D> path = ((PlanResult.Found) result).path().waypoints();
        List<Point2D> waypoints = thin(path, from.position(), goal.pose().position());
        if (waypoints.size() < 2) {
            return new Plan(null, 0, null);
        }
        try {
            MotionLimits planning = owner.currentLimits().withHeadroom(trackerTask.config().speedHeadroom(),
                    trackerTask.config().accelerationHeadroom());
            SplineTrajectory t = SplineTrajectory.planCurvatureLimited(waypoints, planning.maxLinearSpeed(), planning);
            return new Plan(t, t.length(), null);
        } catch (InvalidPathException e) {
            return new Plan(null, 0, "no trajectory through the path: " + e.getMessage());
        }
    }

    /** Keeps a waypoint every {@link #WAYPOINT_SPACING} m, the exact start and the exact goal. */
    static List<Point2D> thin(List<Point2D> path, Point2D start, Point2D goal) {
        List<Point2D> out = new ArrayList<>();
        out.add(start);
        Point2D last = start;
        for (int i = 1; i < path.size() - 1; i++) {
            Point2D p = path.get(i);
            if (Math.hypot(p.x() - last.x(), p.y() - last.y()) >= WAYPOINT_SPACING
                    && Math.hypot(p.x() - goal.x(), p.y() - goal.y()) >= WAYPOINT_SPACING / 2) {
                out.add(p);
                last = p;
            }
        }
        if (Math.hypot(goal.x() - start.x(), goal.y() - start.y()) > 1e-3) {
            out.add(goal);
        }
        return out;
    }

    void startMission(Goal g, Plan plan) {
        double t = now();
        clearFault();
        this.goal = g;
        goalChecker = new GoalChecker(g.positionTolerance(), Math.min(Math.PI, g.headingTolerance()), true);
        setMission(MissionState.RUNNING, 0, "to (" + MotionTask.fmt(g.pose().x()) + ", "
                + MotionTask.fmt(g.pose().y()) + ")");
        if (plan.trajectory() == null) {
            trajectory = null;
            trajectoryPayload = new TrajectoryPayload(Instant.now(), List.of());
            stabilizer.reset();
            positionSettled = false;
            setMode(Mode.SETTLE, t);
            return;
        }
        setTrajectory(plan, t);
    }

    void followImposed(TrajectoryPayload imposed) {
        double t = now();
        clearFault();
        this.goal = null;
        Trajectory path = new SampledTrajectory(imposed.points());
        goalChecker = new GoalChecker(config.goalTolerance(), Math.PI, true);
        setMission(MissionState.RUNNING, 0, "imposed trajectory");
        setTrajectory(new Plan(path, path.length(), null), t);
    }

    private void setTrajectory(Plan plan, double t) {
        trajectory = plan.trajectory();
        trajectoryPayload = new TrajectoryPayload(Instant.now(), MotionTask.sample(trajectory));
        progressChecker = new ProgressChecker(trackerTask.config().progressRadius(), trackerTask.config()
                .progressTime());
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

    void teleop(Twist2D twist, long receivedNanos, Instant sent) {
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
    void teleopWrite() {
        if (mode != Mode.TELEOP || teleopSent == null) {
            return;
        }
        // the silence after the period's last answer has partly or wholly passed while the twist was on its way
        double sinceWork = (System.nanoTime() - timing.lastEndNanos()) * 1e-9;
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
        double left = (timing.nextStartNanos() - System.nanoTime()) * 1e-9;
        return left >= silence + wireTime * WIRE_TIME_FACTOR + PERIOD_MARGIN;
    }

    /** The newest joystick twist has reached the board (through the smoother): its latency is recorded. */
    private void teleopWritten() {
        teleopLatency.add(java.time.Duration.between(teleopSent, Instant.now()).toNanos());
        teleopSent = null;
    }

    /** Writes the joystick's twist through the smoother; records its latency. @return true when written */
    private boolean writeTwist(double t) {
        Twist2D applied = smoother.smooth(t, teleopTwist);
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

    void relocalise(Pose2D p) {
        localizer.reset(p, now());
        LOG.info("re-localised at {}", p);
    }

    void limitsChanged(MotionLimits l) {
        this.limits = l;
        smoother = new VelocitySmoother(l, 1.0);
        tracker = trackerTask.newTracker(l);
        stabilizer = trackerTask.newStabilizer(l);
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

    void pause() {
        if (mission.state() != MissionState.RUNNING) {
            return;
        }
        pausedFrom = mode;
        setMode(Mode.PAUSED, now());
        setMission(MissionState.PAUSED, mission.progress(), "paused");
    }

    void resume() {
        if (mode != Mode.PAUSED) {
            return;
        }
        double t = now();
        setMission(MissionState.RUNNING, mission.progress(), "resumed");
        if (pausedFrom == Mode.FOLLOW || pausedFrom == Mode.ALIGN || pausedFrom == Mode.BLOCKED) {
            // the trajectory's clock went on while paused: plan again from where the robot stands
            setMode(Mode.BLOCKED, t);
            replan(t);
        } else {
            setMode(pausedFrom, t);
        }
    }

    void abort(String reason) {
        double t = now();
        brake();
        if (mission.state() == MissionState.RUNNING || mission.state() == MissionState.PAUSED) {
            setMission(MissionState.ABORTED, mission.progress(), reason);
        }
        setMode(Mode.IDLE, t);
        LOG.info("stopped: {}", reason);
    }

    void maintenance(boolean on, String detail) {
        brake();
        MissionState state = mission.state();
        if (on && (state == MissionState.RUNNING || state == MissionState.PAUSED)) {
            state = MissionState.ABORTED;
            LOG.info("mission aborted for maintenance");
        }
        setMode(Mode.IDLE, now());
        mission = new MissionStatus(state, on, mission.progress(),
                on ? (detail == null || detail.isBlank() ? "maintenance" : detail) : "maintenance ended");
        owner.missionChanged(mission);
        LOG.info("maintenance {}", on ? "on" : "off");
    }

    /** Brakes and marks the mission failed with the reason; the robot stays still until a new command. */
    void fault(String reason) {
        if (mode == Mode.FAULT && reason.equals(mission.detail())) {
            return;
        }
        LOG.warn("fault: {} - braking", reason);
        brake();
        setMode(Mode.FAULT, now());
        mission = new MissionStatus(MissionState.FAILED, mission.maintenance(), mission.progress(), reason);
        owner.missionChanged(mission);
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
            smoother.reset();
        }
        if (mode == Mode.FAULT) {
            setMode(Mode.IDLE, now());
        }
    }

    private void brake() {
        smoother.reset();
        try {
            boards.brake(true);
            braked = true;
        } catch (IOException e) {
            LOG.warn("brake command failed ({}); the motor board's own deadman stops the wheels", e.getMessage());
            braked = true;
        }
    }

    private void complete(double t) {
        setMission(MissionState.DONE, 100, "goal reached");
        setMode(Mode.IDLE, t);
        LOG.info("goal reached at ({}, {}, {})", MotionTask.fmt(pose.x()), MotionTask.fmt(pose.y()),
                MotionTask.fmt(pose.theta()));
    }

    private void fail(String reason) {
        brake();
        setMission(MissionState.FAILED, mission.progress(), reason);
        setMode(Mode.IDLE, now());
        LOG.warn("mission failed: {}", reason);
    }

    private void setMode(Mode m, double t) {
        if (m != mode) {
            LOG.debug("mode {} -> {}", mode, m);
        }
        mode = m;
        modeSince = t;
    }

    private void setMission(MissionState state, double progress, String detail) {
        mission = new MissionStatus(state, mission.maintenance(), progress, detail);
        owner.missionChanged(mission);
    }

    private void updateProgress(double progress) {
        // listeners hear about whole-percent steps only; the snapshot carries the exact figure
        boolean step = Math.floor(progress / 10) != Math.floor(mission.progress() / 10);
        mission = new MissionStatus(mission.state(), mission.maintenance(), progress, mission.detail());
        if (step) {
            owner.missionChanged(mission);
        }
    }

    // ----------------------------------------------------------------------------------------------- snapshot

    MotionTask.Snapshot snapshot(Instant now) {
        PoseEstimate p = new PoseEstimate(now, pose, MotionTask.covariance(localizer.covariance()));
        VelocityCommand v = new VelocityCommand(now, new Twist2D(velocity[0], velocity[1]));
        List<Obstacle> obstacles = new ArrayList<>(echoes.size());
        for (double[] e : echoes) {
            obstacles.add(new Obstacle(e[1], e[2], ECHO_RADIUS));
        }
        boolean moving = mode == Mode.TELEOP || mode == Mode.ALIGN || mode == Mode.FOLLOW || mode == Mode.SETTLE
                || Math.abs(velocity[0]) > 0.02 || Math.abs(velocity[1]) > 0.05;
        return new MotionTask.Snapshot(p, v, mission, Optional.ofNullable(goal), trajectoryPayload,
                new Obstacles(now, obstacles), moving, timing.summary());
    }

    private static String f3(double v) {
        return String.format(Locale.ROOT, "%.3f", v);
    }

    private static String f2(double v) {
        return String.format(Locale.ROOT, "%.2f", v);
    }
}
