package sabot.localization.calibration;

/**
 * One UMBmark run: the robot drove a square of side L under odometry feedback and stopped where its odometry said
 * it started. The result is the true stop position minus the odometry's, in the start frame (x along the initial
 * heading, y to its left), as measured with a tape or a ground-truth system.
 *
 * @param clockwise true for a clockwise (right-turning) square
 * @param errorX    metres
 * @param errorY    metres
 */
public record SquareRunResult(boolean clockwise, double errorX, double errorY) {

    public SquareRunResult {
        if (!Double.isFinite(errorX) || !Double.isFinite(errorY)) {
            throw new IllegalArgumentException("run errors must be finite");
        }
    }
}
