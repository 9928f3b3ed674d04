package sabot.model.path;

import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;

/**
 * The reference state of a unicycle at one instant: what a tracking controller needs as feedforward.
 * <p>
 * The Cartesian derivatives are those of the flat output (x, y), which is what dynamic feedback linearization
 * uses; the unicycle quantities (heading, v, &omega;) are those the pseudoinverse controller uses. They are
 * consistent: {@code xDot = v cos(theta)}, {@code yDot = v sin(theta)}, {@code omega = (xDot*yDdot - yDot*xDdot)/v^2}.
 *
 * @param time            seconds since the trajectory's start
 * @param x               metres, map frame
 * @param y               metres, map frame
 * @param theta           heading in radians (may grow beyond &pi; on closed paths; compare angles modulo 2&pi;)
 * @param linearVelocity  v_d in m/s (negative when the reference drives backwards)
 * @param angularVelocity &omega;_d in rad/s
 * @param xDot            m/s
 * @param yDot            m/s
 * @param xDdot           m/s&sup2;
 * @param yDdot           m/s&sup2;
 */
public record TrajectorySample(double time, double x, double y, double theta, double linearVelocity,
        double angularVelocity, double xDot, double yDot, double xDdot, double yDdot) {

    /** @return a reference that stands still at {@code pose} */
    public static TrajectorySample stationary(double time, Pose2D pose) {
        return new TrajectorySample(time, pose.x(), pose.y(), pose.theta(), 0, 0, 0, 0, 0, 0);
    }

    /** @return position and heading of the reference */
    public Pose2D pose() {
        return new Pose2D(x, y, theta);
    }

    /** @return (v_d, &omega;_d) */
    public Twist2D twist() {
        return new Twist2D(linearVelocity, angularVelocity);
    }

    /** @return true when every component is finite */
    public boolean isFinite() {
        return Double.isFinite(time) && Double.isFinite(x) && Double.isFinite(y) && Double.isFinite(theta)
                && Double.isFinite(linearVelocity) && Double.isFinite(angularVelocity) && Double.isFinite(xDot)
                && Double.isFinite(yDot) && Double.isFinite(xDdot) && Double.isFinite(yDdot);
    }
}
