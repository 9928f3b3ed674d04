package sabot.control;

/**
 * Angular speeds of the two drive wheels.
 *
 * @param left  rad/s, positive drives the robot forward
 * @param right rad/s, positive drives the robot forward
 */
public record WheelSpeeds(double left, double right) {

    public static final WheelSpeeds ZERO = new WheelSpeeds(0, 0);

    /** @return true when both are finite */
    public boolean isFinite() {
        return Double.isFinite(left) && Double.isFinite(right);
    }
}
