package sabot.control;

import sabot.model.robot.RobotDescription;

/**
 * The speed and acceleration envelope commands must stay in.
 *
 * @param maxLinearSpeed         |v| bound, m/s
 * @param maxLinearAcceleration  bound on |dv/dt| and on each wheel's rim acceleration, m/s&sup2;
 * @param maxAngularSpeed        |&omega;| bound, rad/s
 * @param maxLateralAcceleration |v&middot;&omega;| bound a trajectory may plan for, m/s&sup2;
 * @param maxWheelRimSpeed       bound on each wheel's rim speed (motor no-load speed through the gearhead), m/s
 * @param trackWidth             wheel separation, m (needed to turn twist limits into wheel limits)
 */
public record MotionLimits(double maxLinearSpeed, double maxLinearAcceleration, double maxAngularSpeed,
        double maxLateralAcceleration, double maxWheelRimSpeed, double trackWidth) {

    public MotionLimits {
        for (double v : new double[] { maxLinearSpeed, maxLinearAcceleration, maxAngularSpeed, maxLateralAcceleration,
                maxWheelRimSpeed, trackWidth }) {
            if (!Double.isFinite(v) || v <= 0) {
                throw new IllegalArgumentException("motion limits must be finite and > 0: " + v);
            }
        }
    }

    /** @return the limits of the described robot */
    public static MotionLimits of(RobotDescription robot) {
        return new MotionLimits(robot.maxLinearSpeed(), robot.maxLinearAcceleration(), robot.maxAngularSpeed(),
                robot.maxLateralAcceleration(), robot.maxWheelRimSpeed(), robot.trackWidth());
    }

    /**
     * A planning envelope inside this one: speeds and accelerations (linear, lateral, angular) scaled by
     * {@code fraction}, wheel and track unchanged. A trajectory planned at the full limits leaves the feedback no
     * authority (any correction of a lag while the reference accelerates at a_max is clipped); plan with, e.g.,
     * {@code withHeadroom(0.8)} and let the controller and smoother use the rest.
     *
     * @param fraction in (0, 1]
     */
    public MotionLimits withHeadroom(double fraction) {
        return withHeadroom(fraction, fraction);
    }

    /**
     * A planning envelope with separate fractions for the top speeds (linear, angular) and for the accelerations
     * (linear, lateral, angular). The feedback needs authority mostly in acceleration: a lag while cruising is made up
     * when the reference slows down, but a lag while it accelerates at the bound is not.
     *
     * @param speedFraction        in (0, 1]
     * @param accelerationFraction in (0, 1]
     */
    public MotionLimits withHeadroom(double speedFraction, double accelerationFraction) {
        if (!(speedFraction > 0 && speedFraction <= 1) || !(accelerationFraction > 0 && accelerationFraction <= 1)) {
            throw new IllegalArgumentException("headroom fractions must be in (0, 1], were " + speedFraction + " and "
                    + accelerationFraction);
        }
        return new MotionLimits(maxLinearSpeed * speedFraction, maxLinearAcceleration * accelerationFraction,
                maxAngularSpeed * speedFraction, maxLateralAcceleration * accelerationFraction, maxWheelRimSpeed,
                trackWidth);
    }

    /**
     * @return the yaw acceleration bound implied by the wheel rim acceleration bound: 2&middot;a_max/d, rad/s&sup2;
     */
    public double maxAngularAcceleration() {
        return 2 * maxLinearAcceleration / trackWidth;
    }

    /** @return the largest speed at which a path of curvature {@code curvature} (1/m) can be driven, m/s */
    public double maxSpeedForCurvature(double curvature) {
        double k = Math.abs(curvature);
        double v = maxLinearSpeed;
        if (k > 0) {
            v = Math.min(v, Math.sqrt(maxLateralAcceleration / k));
            v = Math.min(v, maxAngularSpeed / k);
        }
        // rim speed of the outer wheel: v (1 + k d/2)
        return Math.min(v, maxWheelRimSpeed / (1 + k * trackWidth / 2));
    }
}
