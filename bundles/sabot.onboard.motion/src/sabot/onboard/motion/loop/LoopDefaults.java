package sabot.onboard.motion.loop;

import sabot.control.Controllers;
import sabot.control.DflGains;
import sabot.control.MotionLimits;
import sabot.control.TrackingController;
import sabot.model.geometry.Pose2D;

/**
 * The shipped defaults of the motion tasks' settings ({@code motion}, {@code teleop}, {@code planner},
 * {@code tracker}, {@code localizer}): the one source of each value. The tasks' Metatype descriptions take their
 * defaults from these constants (so does {@code etc/onboard.conf}'s commented list, checked against the Metatype by
 * the onboard tests), and whoever runs the loop outside the product (the motion simulation) builds the robot as
 * shipped from {@link #settings} and {@link #controllers}.
 */
public final class LoopDefaults {

    // motion task
    /** {@code motion.rate}, Hz. */
    public static final double RATE = 50;
    /** {@code motion.statusPeriod}, s. */
    public static final double STATUS_PERIOD = 1;
    /** {@code motion.obstacleMemory}, s. */
    public static final double OBSTACLE_MEMORY = 3;
    /** {@code motion.blockedLookahead}, s. */
    public static final double BLOCKED_LOOKAHEAD = 3;
    /** {@code motion.blockedClearance}, m. */
    public static final double BLOCKED_CLEARANCE = 0.05;
    /** {@code motion.goalTolerance}, m. */
    public static final double GOAL_TOLERANCE = 0.1;
    /** {@code motion.guardMargin}, m: the collision guard stops the robot this far short of an obstacle. */
    public static final double GUARD_MARGIN = 0.05;
    /**
     * {@code motion.guardReactionTime}, s: from a command to the wheels braking — up to a period before the loop
     * writes it, the write itself, and the motor board's speed loop taking it.
     */
    public static final double GUARD_REACTION_TIME = 0.06;
    /** {@code motion.reverseSpeed}, m/s: the top speed backwards, where no sensor looks. */
    public static final double REVERSE_SPEED = 0.1;
    /**
     * {@code motion.batteryLow}, 0–1: below this state of charge the robot aborts its mission and goes to its dock. A
     * fifth of the charge: the lab is crossed in a minute at a fraction of a per cent, and a lithium-ion pack kept
     * above 20 % ages more slowly.
     */
    public static final double BATTERY_LOW = 0.2;
    /** {@code motion.batteryCharged}, 0–1: a robot charging after a low battery is free again at this charge. */
    public static final double BATTERY_CHARGED = 0.9;
    /**
     * {@code motion.peerMemory}, s: another robot not heard from for this long stops being an obstacle of the planner
     * and the collision guard (its body is left to the sonar). Long enough to outlast a reconnection of either robot's
     * session (a few seconds), short enough that a robot switched off and carried away does not block a door for good.
     */
    public static final double PEER_MEMORY = 30;
    /**
     * {@code motion.passageApproach}, m: a passage of the map is asked for when the path enters it within this
     * distance. The robot that yields stops about 1.25 m short of it (less the braking distance from the top speed,
     * 0.25 m): room for the robot coming through to leave the passage and drive round it.
     */
    public static final double PASSAGE_APPROACH = 1.5;
    /** {@code motion.passageTimeout}, s: the longest a robot waits for its turn at a passage before its mission fails. */
    public static final double PASSAGE_TIMEOUT = 120;

    // teleop task
    /** {@code teleop.timeout}, s: the loop's deadman, also while the teleop task does not run. */
    public static final double DEADMAN = 0.5;
    /**
     * {@code teleop.maxAge}, s: a twist sent longer ago is dropped. The deadman's time: a twist the deadman would
     * already have braked for must not drive.
     */
    public static final double TELEOP_MAX_AGE = DEADMAN;

    // planner task
    /** {@code planner.algorithm}. */
    public static final String PLANNER_ALGORITHM = "lpn";
    /** {@code planner.threads}. */
    public static final int PLANNER_THREADS = 1;
    /** {@code planner.robotRadius}, m. */
    public static final double ROBOT_RADIUS = 0.25;
    /** {@code planner.inflationRadius}, m. */
    public static final double INFLATION_RADIUS = 0.55;
    /** {@code planner.blockedTimeout}, s. */
    public static final double BLOCKED_TIMEOUT = 10;

    // tracker task
    /** {@code tracker.omegaN}, rad/s: the DFL tracker's natural frequency. */
    public static final double OMEGA_N = 2.0;
    /** {@code tracker.zeta}: the DFL tracker's damping ratio. */
    public static final double ZETA = 0.9;
    /** {@code tracker.kp}, 1/s: the pseudoinverse tracker's position gain. */
    public static final double KP = 1.5;
    /** {@code tracker.kTheta}, 1/s: the pseudoinverse tracker's heading gain. */
    public static final double K_THETA = 2.0;
    /** {@code tracker.stabilizerRate}, 1/s: the DFL point stabilizer's rate. */
    public static final double STABILIZER_RATE = 0.5;
    /** {@code tracker.speedHeadroom}. */
    public static final double SPEED_HEADROOM = 0.95;
    /** {@code tracker.accelerationHeadroom}. */
    public static final double ACCELERATION_HEADROOM = 0.8;
    /** {@code tracker.progressRadius}, m. */
    public static final double PROGRESS_RADIUS = 0.1;
    /** {@code tracker.progressTime}, s. */
    public static final double PROGRESS_TIME = 8;
    /** {@code tracker.settleTimeout}, s. */
    public static final double SETTLE_TIMEOUT = 15;

    // localizer task
    /** {@code localizer.initialSigmaXY}, m. */
    public static final double INITIAL_SIGMA_XY = 0.02;
    /** {@code localizer.initialSigmaTheta}, rad. */
    public static final double INITIAL_SIGMA_THETA = 0.02;
    /** {@code localizer.useImu}. */
    public static final boolean USE_IMU = true;
    /** {@code localizer.useAccelerometer}. */
    public static final boolean USE_ACCELEROMETER = true;
    /** {@code localizer.imuSettleTime}, s. */
    public static final double IMU_SETTLE_TIME = 3;
    /** {@code localizer.odometryTimeout}, s. */
    public static final double ODOMETRY_TIMEOUT = 0.2;
    /** {@code localizer.useLandmarks}. */
    public static final boolean USE_LANDMARKS = true;
    /** {@code localizer.landmarkRangeSigma}, m. */
    public static final double LANDMARK_RANGE_SIGMA = 0.02;
    /** {@code localizer.landmarkBearingSigma}, rad. */
    public static final double LANDMARK_BEARING_SIGMA = 0.02;
    /** {@code localizer.maxPositionSigma}, m. */
    public static final double MAX_POSITION_SIGMA = 0.5;

    private LoopDefaults() {
    }

    /** @return the loop's settings as shipped, the robot starting at {@code start}, the joystick accepted */
    public static LoopSettings settings(Pose2D start) {
        return new LoopSettings(RATE, STATUS_PERIOD, OBSTACLE_MEMORY, BLOCKED_LOOKAHEAD, BLOCKED_CLEARANCE,
                GOAL_TOLERANCE, true, DEADMAN, ROBOT_RADIUS, BLOCKED_TIMEOUT, SPEED_HEADROOM, ACCELERATION_HEADROOM,
                PROGRESS_RADIUS, PROGRESS_TIME, SETTLE_TIMEOUT, localizer(start), guard());
    }

    /** @return the other robots' settings as shipped */
    public static PeerSettings peers() {
        return new PeerSettings(PEER_MEMORY, PASSAGE_APPROACH, PASSAGE_TIMEOUT);
    }

    /** @return the collision guard's settings as shipped */
    public static GuardSettings guard() {
        return new GuardSettings(GUARD_MARGIN, GUARD_REACTION_TIME, REVERSE_SPEED);
    }

    /** @return the localizer's settings as shipped, the robot starting at {@code start} */
    public static LocalizerSettings localizer(Pose2D start) {
        return new LocalizerSettings(start, INITIAL_SIGMA_XY, INITIAL_SIGMA_THETA, USE_IMU, USE_ACCELEROMETER,
                IMU_SETTLE_TIME, ODOMETRY_TIMEOUT, LANDMARK_RANGE_SIGMA, LANDMARK_BEARING_SIGMA, MAX_POSITION_SIGMA);
    }

    /** @return the tracker task's default control laws: the DFL tracker and the DFL point stabilizer */
    public static LoopControllers controllers() {
        return new LoopControllers() {
            @Override
            public TrackingController tracker(MotionLimits limits) {
                return Controllers.dynamicFeedbackLinearization(DflGains.of(OMEGA_N, ZETA), limits);
            }

            @Override
            public TrackingController stabilizer(MotionLimits limits) {
                return Controllers.dflPointStabilization(DflGains.stabilizing(STABILIZER_RATE), limits);
            }
        };
    }
}
