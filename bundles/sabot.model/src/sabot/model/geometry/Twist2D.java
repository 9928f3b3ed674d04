package sabot.model.geometry;

/**
 * A planar velocity command or estimate of a unicycle-type robot, in the robot's own frame.
 *
 * @param linear  forward speed in metres per second
 * @param angular yaw rate in radians per second, counter-clockwise positive
 */
public record Twist2D(double linear, double angular) {

    public static final Twist2D ZERO = new Twist2D(0, 0);

    /** @return true when both components are finite */
    public boolean isFinite() {
        return Double.isFinite(linear) && Double.isFinite(angular);
    }
}
