package sabot.control;

import sabot.model.geometry.Pose2D;

/**
 * Stuck detection, like Nav2's {@code SimpleProgressChecker}: the robot must move at least
 * {@code requiredMovementRadius} from where it was last seen progressing within {@code movementTimeAllowance}.
 */
public final class ProgressChecker {

    private final double radius;
    private final double allowance;
    private Pose2D baseline;
    private double baselineTime = Double.NaN;

    /**
     * @param requiredMovementRadius metres
     * @param movementTimeAllowance  seconds
     */
    public ProgressChecker(double requiredMovementRadius, double movementTimeAllowance) {
        if (!(requiredMovementRadius > 0) || !(movementTimeAllowance > 0)) {
            throw new IllegalArgumentException("radius and time allowance must be > 0");
        }
        this.radius = requiredMovementRadius;
        this.allowance = movementTimeAllowance;
    }

    /**
     * @param time seconds, monotonic; a time earlier than the baseline restarts the check
     * @param pose current pose estimate; a non-finite pose counts as no progress
     * @return false when the robot has not left the baseline circle within the allowance (stuck)
     */
    public boolean isMakingProgress(double time, Pose2D pose) {
        if (!Double.isFinite(time)) {
            return false;
        }
        boolean finitePose = pose != null && pose.isFinite();
        if (baseline == null || time < baselineTime) {
            if (!finitePose) {
                return false;
            }
            baseline = pose;
            baselineTime = time;
            return true;
        }
        if (finitePose && Math.hypot(pose.x() - baseline.x(), pose.y() - baseline.y()) > radius) {
            baseline = pose;
            baselineTime = time;
            return true;
        }
        return time - baselineTime <= allowance;
    }

    public void reset() {
        baseline = null;
        baselineTime = Double.NaN;
    }
}
