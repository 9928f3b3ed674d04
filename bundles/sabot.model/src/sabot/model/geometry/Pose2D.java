package sabot.model.geometry;

/**
 * A planar pose: position and heading of the robot's centre in a frame.
 *
 * @param x     metres
 * @param y     metres
 * @param theta heading in radians, counter-clockwise from the frame's x axis; not normalised by the constructor
 */
public record Pose2D(double x, double y, double theta) {

    public static final Pose2D ORIGIN = new Pose2D(0, 0, 0);

    /** @return the position part of this pose */
    public Point2D position() {
        return new Point2D(x, y);
    }

    /** @return true when all three components are finite */
    public boolean isFinite() {
        return Double.isFinite(x) && Double.isFinite(y) && Double.isFinite(theta);
    }

    /** @return this pose with its heading wrapped into (-pi, pi] */
    public Pose2D normalized() {
        return new Pose2D(x, y, normalizeAngle(theta));
    }

    /** Wraps an angle in radians into (-pi, pi]. */
    public static double normalizeAngle(double angle) {
        double a = Math.IEEEremainder(angle, 2 * Math.PI);
        return a <= -Math.PI ? a + 2 * Math.PI : a;
    }
}
