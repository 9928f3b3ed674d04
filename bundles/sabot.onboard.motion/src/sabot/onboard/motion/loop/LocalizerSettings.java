package sabot.onboard.motion.loop;

import sabot.model.geometry.Pose2D;

/**
 * What the pose estimate is configured with (the {@code localizer} task's settings, one immutable snapshot).
 *
 * @param start                where the robot stands at the start, map frame
 * @param initialSigmaXY       initial standard deviation of x and y, m
 * @param initialSigmaTheta    initial standard deviation of the heading, rad
 * @param useImu               fuse the inertial board's gyro
 * @param useAccelerometer     also fuse its longitudinal accelerometer
 * @param imuSettleTime        s the robot stays still after the start while the inertial biases are learnt
 * @param odometryTimeout      s without encoder readings after which the estimate is stale (the robot stops)
 * @param landmarkRangeSigma   standard deviation of a landmark's range, m
 * @param landmarkBearingSigma standard deviation of a landmark's bearing, rad
 * @param maxPositionSigma     positional standard deviation, m, above which the robot stops
 */
public record LocalizerSettings(Pose2D start, double initialSigmaXY, double initialSigmaTheta, boolean useImu,
        boolean useAccelerometer, double imuSettleTime, double odometryTimeout, double landmarkRangeSigma,
        double landmarkBearingSigma, double maxPositionSigma) {
}
