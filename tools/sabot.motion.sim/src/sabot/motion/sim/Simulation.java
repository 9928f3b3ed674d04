package sabot.motion.sim;

import java.util.ArrayList;
import java.util.List;
import java.util.Random;

import sabot.control.ControlCommand;
import sabot.control.ControlStatus;
import sabot.control.DifferentialDrive;
import sabot.control.GoalChecker;
import sabot.control.MotionLimits;
import sabot.control.TrackingController;
import sabot.control.VelocitySmoother;
import sabot.localization.EkfNoise;
import sabot.localization.EncoderOdometry;
import sabot.localization.OdometryCalibration;
import sabot.localization.PoseEkf;
import sabot.localization.calibration.SquareRunResult;
import sabot.localization.calibration.UmbmarkCalibration;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.path.Trajectory;
import sabot.model.path.TrajectorySample;
import sabot.model.robot.RobotDescription;
import sabot.onboard.motion.loop.LoopDefaults;

/**
 * The algorithm study: runs a scenario closed-loop, sensors &rarr; estimator &rarr; controller &rarr; velocity smoother
 * &rarr; wheel speeds &rarr; ground-truth robot, once per control period, and computes the figures. One control law on
 * one feedback along a given trajectory; the robot's own loop on the same simulated robot is {@link OnboardLoop}.
 */
public final class Simulation {

    /** Number of random starts of the stabilization scenario. */
    public static final int STABILIZATION_STARTS = 20;
    /** Radius of the goal region that ends a stabilization run, metres (Nav2-style goal checker). */
    public static final double STABILIZATION_TOLERANCE = 0.005;
    /** Tracking error bound used for the settle time, metres. */
    public static final double SETTLE_BOUND = 0.02;
    /** Seconds after the reference starts from which RMS and max errors are taken. */
    public static final double TRANSIENT = 5.0;
    /** UMBmark: runs per direction. */
    public static final int CALIBRATION_RUNS_PER_DIRECTION = 5;
    /** Command timeout of the study's velocity smoother, s: the robot's deadman as shipped. */
    static final double SMOOTHER_TIMEOUT = LoopDefaults.DEADMAN;
    /** Odometry age after which the EKF estimate is stale, s: the localizer's as shipped. */
    static final double ODOMETRY_TIMEOUT = LoopDefaults.ODOMETRY_TIMEOUT;

    private Simulation() {
    }

    /** Runs the configured scenario (and the calibration squares first when asked). */
    public static SimulationResult run(SimulationConfig c) {
        RobotDescription robot = c.robot();
        MotionLimits limits = MotionLimits.of(robot);
        OdometryCalibration geometry = OdometryCalibration.nominal(robot);
        List<SquareRunResult> calibrationRuns = List.of();
        if (c.calibrated()) {
            calibrationRuns = calibrationRuns(c, geometry);
            geometry = new UmbmarkCalibration(Scenario.SQUARE_SIDE).calibrate(calibrationRuns, geometry);
        }
        Trace trace = new Trace();
        Metrics metrics;
        if (c.scenario() == Scenario.STABILIZE) {
            metrics = stabilize(c, limits, geometry, trace);
        } else {
            Trajectory ref = c.scenario().trajectory(limits, c.fromVertex());
            Pose2D refStart = ref.startPose();
            Pose2D start = c.scenario() == Scenario.OFFSET
                    ? new Pose2D(refStart.x() + Scenario.OFFSET_ERROR.x(), refStart.y() + Scenario.OFFSET_ERROR.y(),
                            refStart.theta() + Scenario.OFFSET_ERROR.theta())
                    : refStart;
            RunOutcome o = drive(c, ref, start, c.controller().tracking(limits), geometry, c.seed(), 0,
                    ref.duration() + c.holdTime(), false, trace);
            metrics = trackingMetrics(c, ref, start, o, trace);
        }
        return new SimulationResult(c, trace, metrics, geometry, calibrationRuns);
    }

    /** UMBmark: clockwise and counter-clockwise squares under odometry feedback; errors in the start frame. */
    static List<SquareRunResult> calibrationRuns(SimulationConfig c, OdometryCalibration geometry) {
        MotionLimits limits = MotionLimits.of(c.robot());
        SimulationConfig odo = c.with(Scenario.SQUARE, c.controller(), Feedback.ODOMETRY);
        List<SquareRunResult> runs = new ArrayList<>();
        for (int i = 0; i < 2 * CALIBRATION_RUNS_PER_DIRECTION; i++) {
            boolean cw = i % 2 == 0;
            Trajectory square = Scenario.square(Scenario.SQUARE_SIDE, cw, limits);
            RunOutcome o = drive(odo, square, Pose2D.ORIGIN, c.controller().tracking(limits), geometry,
                    c.seed() * 1000 + 17 + i, i, square.duration() + 1.0, false, null);
            runs.add(new SquareRunResult(cw, o.truth.x() - o.estimate.x(), o.truth.y() - o.estimate.y()));
        }
        return runs;
    }

    private static Metrics stabilize(SimulationConfig c, MotionLimits limits, OdometryCalibration geometry, Trace trace) {
        Random starts = new Random(c.seed());
        Pose2D goal = Pose2D.ORIGIN;
        double worst = 0;
        double worstHeading = 0;
        int violations = 0;
        int nans = 0;
        double maxYaw = 0;
        double worstEstimate = 0;
        for (int i = 0; i < STABILIZATION_STARTS; i++) {
            double radius = 0.5 + 1.5 * starts.nextDouble();
            double bearing = 2 * Math.PI * starts.nextDouble();
            double heading = Math.PI * (2 * starts.nextDouble() - 1);
            Pose2D start = new Pose2D(radius * Math.cos(bearing), radius * Math.sin(bearing), heading);
            Trace run = new Trace();
            RunOutcome o = drive(c, new StationaryTrajectory(goal, 60), start, c.controller().stabilizing(limits),
                    geometry, c.seed() * 7919 + i, i, 60, true, run);
            trace.append(run);
            worst = Math.max(worst, Math.hypot(o.truth.x() - goal.x(), o.truth.y() - goal.y()));
            worstHeading = Math.max(worstHeading, Math.abs(Pose2D.normalizeAngle(o.truth.theta() - goal.theta())));
            worstEstimate = Math.max(worstEstimate, Math.hypot(o.truth.x() - o.estimate.x(), o.truth.y() - o.estimate.y()));
            violations += o.violations;
            nans += o.nans;
            maxYaw = Math.max(maxYaw, o.maxYaw);
        }
        return new Metrics(Double.NaN, Double.NaN, Double.NaN, worst, worstHeading, Double.NaN, worstEstimate, violations,
                nans, maxYaw);
    }

    private static Metrics trackingMetrics(SimulationConfig c, Trajectory ref, Pose2D start, RunOutcome o, Trace trace) {
        int tc = Trace.column("t_s");
        int ec = Trace.column("error_m");
        double sum = 0;
        int n = 0;
        double max = 0;
        double lastBad = Double.NaN;
        boolean everBad = false;
        for (int r = 0; r < trace.size(); r++) {
            double t = trace.get(r, tc);
            double e = trace.get(r, ec);
            if (t >= 0 && t <= ref.duration() && e > SETTLE_BOUND) {
                lastBad = t;
                everBad = true;
            }
            if (t >= TRANSIENT && t <= ref.duration()) {
                sum += e * e;
                n++;
                max = Math.max(max, e);
            }
        }
        double settle = !everBad ? 0 : lastBad >= ref.duration() - 1e-9 ? Double.NaN : lastBad + c.robot().controlPeriod();
        Pose2D end = ref.endPose();
        double ret = c.scenario().isClosed() ? Math.hypot(o.truth.x() - start.x(), o.truth.y() - start.y()) : Double.NaN;
        return new Metrics(n == 0 ? Double.NaN : Math.sqrt(sum / n), n == 0 ? Double.NaN : max, ret,
                Math.hypot(o.truth.x() - end.x(), o.truth.y() - end.y()), Double.NaN, settle,
                Math.hypot(o.truth.x() - o.estimate.x(), o.truth.y() - o.estimate.y()), o.violations, o.nans, o.maxYaw);
    }

    /** End state and counters of one closed-loop run. */
    record RunOutcome(Pose2D truth, Pose2D estimate, int violations, int nans, double maxYaw) {
    }

    /**
     * One closed-loop run from {@code -settleTime} to {@code endTime} (reference clock).
     *
     * @param stopAtGoal end the run (after bringing the robot to rest) once the goal checker is satisfied
     * @param trace      receives the rows; may be null
     */
    static RunOutcome drive(SimulationConfig c, Trajectory ref, Pose2D start, TrackingController controller,
            OdometryCalibration geometry, long seed, int runIndex, double endTime, boolean stopAtGoal, Trace trace) {
        RobotDescription robot = c.robot();
        MotionLimits limits = MotionLimits.of(robot);
        DifferentialDrive drive = DifferentialDrive.of(robot);
        double period = robot.controlPeriod();
        SimulatedRobot truth = new SimulatedRobot(robot, start, c.slipNoise(), c.slipBias(), seed * 31 + 1);
        SimulatedImu imu = new SimulatedImu(c.mems(), seed * 31 + 2);
        EncoderOdometry odometry = new EncoderOdometry(robot, geometry, start);
        odometry.update(truth.leftCount(), truth.rightCount());
        PoseEkf ekf = null;
        if (c.feedback() == Feedback.EKF) {
            ekf = new PoseEkf(start, new double[] { 0.005, 0.005, Math.toRadians(0.5) }, EkfNoise.defaults(),
                    ODOMETRY_TIMEOUT);
            ekf.start(-c.settleTime());
        }
        int magEvery = Math.max(1, (int) Math.round(1 / (c.mems().magnetometerRate() * period)));
        VelocitySmoother smoother = new VelocitySmoother(limits, SMOOTHER_TIMEOUT);
        GoalChecker goalChecker = new GoalChecker(STABILIZATION_TOLERANCE, Math.PI, true);
        Twist2D previous = Twist2D.ZERO;
        int violations = 0;
        int nans = 0;
        double maxYaw = 0;
        double stopAt = Double.NaN;
        long steps = Math.round((endTime + c.settleTime()) / period);
        for (long k = 0; k <= steps; k++) {
            double t = -c.settleTime() + k * period;
            boolean odometryAlive = Double.isNaN(c.odometryDropout()) || t < c.odometryDropout();
            if (k > 0) {
                if (odometryAlive) {
                    odometry.update(truth.leftCount(), truth.rightCount());
                }
                if (ekf != null) {
                    if (odometryAlive) {
                        ekf.updateOdometry(t, period, odometry.lastDistance(), odometry.lastRotation());
                    }
                    ekf.updateGyro(t, imu.gyro(truth.lastTwist().angular()));
                    ekf.updateAccelerometer(t, imu.accelerometer(truth.lastAcceleration()));
                    if (k % magEvery == 0) {
                        ekf.updateHeading(t, imu.heading(truth.pose().theta()));
                    }
                }
            }
            Pose2D estimate;
            boolean stale;
            switch (c.feedback()) {
                case TRUTH -> {
                    estimate = truth.pose();
                    stale = false;
                }
                case ODOMETRY -> {
                    estimate = odometry.pose();
                    stale = !odometryAlive;
                }
                default -> {
                    ekf.predict(t);
                    estimate = ekf.pose();
                    stale = ekf.isStale(t);
                }
            }
            TrajectorySample r = ref.sample(t);
            ControlCommand command;
            if (stale) {
                command = ControlCommand.stop(ControlStatus.STOPPED_INVALID_POSE);
            } else if (t < 0) {
                // Start-up: the robot stands still while the IMU biases settle; the controller is not engaged.
                command = ControlCommand.stop(ControlStatus.REGULATING_AT_REST);
            } else if (stopAtGoal && goalChecker.isGoalReached(estimate, r.pose())) {
                command = ControlCommand.stop(ControlStatus.REGULATING_AT_REST);
                if (Double.isNaN(stopAt)) {
                    stopAt = t;
                }
            } else {
                command = controller.update(t, estimate, r);
            }
            Twist2D applied = smoother.smooth(t, command.twist());
            if (!applied.isFinite()) {
                nans++;
                applied = Twist2D.ZERO;
            }
            controller.commandApplied(applied);
            if (violates(applied, previous, limits, k == 0 ? Double.NaN : period)) {
                violations++;
            }
            maxYaw = Math.max(maxYaw, Math.abs(applied.angular()));
            previous = applied;
            if (trace != null) {
                Pose2D p = truth.pose();
                trace.add(command.status().name(), runIndex, t, r.x(), r.y(), r.theta(), p.x(), p.y(), p.theta(),
                        estimate.x(), estimate.y(), estimate.theta(), applied.linear(), applied.angular(),
                        Math.hypot(p.x() - r.x(), p.y() - r.y()), Math.hypot(p.x() - estimate.x(), p.y() - estimate.y()));
            }
            if (!Double.isNaN(stopAt) && t - stopAt > 1.0) {
                break;
            }
            truth.step(drive.toWheelSpeeds(applied), period);
            imu.advance(period);
        }
        Pose2D finalEstimate = switch (c.feedback()) {
            case TRUTH -> truth.pose();
            case ODOMETRY -> odometry.pose();
            default -> ekf.pose();
        };
        return new RunOutcome(truth.pose(), finalEstimate, violations, nans, maxYaw);
    }

    /** @return true when {@code t} breaks a speed limit or, against {@code previous}, an acceleration limit */
    static boolean violates(Twist2D t, Twist2D previous, MotionLimits limits, double dt) {
        double eps = 1e-9;
        double half = limits.trackWidth() / 2;
        double l = t.linear() - half * t.angular();
        double r = t.linear() + half * t.angular();
        if (Math.abs(t.linear()) > limits.maxLinearSpeed() * (1 + eps)
                || Math.abs(t.angular()) > limits.maxAngularSpeed() * (1 + eps)
                || Math.max(Math.abs(l), Math.abs(r)) > limits.maxWheelRimSpeed() * (1 + eps)) {
            return true;
        }
        if (Double.isNaN(dt)) {
            return false;
        }
        double l0 = previous.linear() - half * previous.angular();
        double r0 = previous.linear() + half * previous.angular();
        double maxStep = limits.maxLinearAcceleration() * dt * (1 + eps) + 1e-12;
        return Math.abs(l - l0) > maxStep || Math.abs(r - r0) > maxStep
                || Math.abs(t.linear() - previous.linear()) > maxStep;
    }
}
