package sabot.localization;

import sabot.model.robot.RobotDescription;

/**
 * The geometry odometry uses: each wheel's effective radius and the effective track.
 *
 * @param leftWheelRadius  metres
 * @param rightWheelRadius metres
 * @param trackWidth       metres
 */
public record OdometryCalibration(double leftWheelRadius, double rightWheelRadius, double trackWidth) {

    public OdometryCalibration {
        for (double v : new double[] { leftWheelRadius, rightWheelRadius, trackWidth }) {
            if (!(v > 0) || !Double.isFinite(v)) {
                throw new IllegalArgumentException("wheel radii and track must be finite and > 0, got " + v);
            }
        }
    }

    /** @return the nominal geometry of the described robot (both radii equal) */
    public static OdometryCalibration nominal(RobotDescription robot) {
        return new OdometryCalibration(robot.wheelRadius(), robot.wheelRadius(), robot.trackWidth());
    }

    /** @return D_R/D_L, the wheel-diameter ratio UMBmark calls E_d */
    public double diameterRatio() {
        return rightWheelRadius / leftWheelRadius;
    }
}
