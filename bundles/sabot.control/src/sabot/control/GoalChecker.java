package sabot.control;

import sabot.model.geometry.Pose2D;

/**
 * Decides that a goal pose is reached, like Nav2's {@code SimpleGoalChecker}: the position within
 * {@code xyTolerance} and the heading within {@code yawTolerance}. When {@code stateful}, once the position has been
 * within tolerance it is taken as reached until {@link #reset()}, so a robot that rotates in place at the goal
 * and drifts by a millimetre is not sent back.
 */
public final class GoalChecker {

    private final double xyTolerance;
    private final double yawTolerance;
    private final boolean stateful;
    private boolean positionLatched;

    /**
     * @param xyTolerance  metres, &gt; 0
     * @param yawTolerance radians, &gt; 0 (use &pi; to ignore the heading)
     * @param stateful     latch the position check
     */
    public GoalChecker(double xyTolerance, double yawTolerance, boolean stateful) {
        if (!(xyTolerance > 0) || !(yawTolerance > 0) || !Double.isFinite(xyTolerance) || !Double.isFinite(yawTolerance)) {
            throw new IllegalArgumentException("tolerances must be finite and > 0");
        }
        this.xyTolerance = xyTolerance;
        this.yawTolerance = yawTolerance;
        this.stateful = stateful;
    }

    /** @return true when {@code pose} is within tolerance of {@code goal}; false when either is not finite */
    public boolean isGoalReached(Pose2D pose, Pose2D goal) {
        if (pose == null || goal == null || !pose.isFinite() || !goal.isFinite()) {
            return false;
        }
        boolean inPosition = positionLatched || Math.hypot(pose.x() - goal.x(), pose.y() - goal.y()) <= xyTolerance;
        if (stateful && inPosition) {
            positionLatched = true;
        }
        return inPosition && Math.abs(Pose2D.normalizeAngle(pose.theta() - goal.theta())) <= yawTolerance;
    }

    public void reset() {
        positionLatched = false;
    }
}
