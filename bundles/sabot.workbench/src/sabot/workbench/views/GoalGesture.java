package sabot.workbench.views;

import org.eclipse.swt.graphics.Point;

import sabot.controlml.payload.Goal;
import sabot.model.geometry.Pose2D;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.map.MapViewport;

/**
 * The operator's goal gesture on the map: press at the target, drag for the heading, release to send. A click without
 * drag faces away from the robot's position. Holds the press while the button is down; the view sends what
 * {@link #release} gives.
 */
final class GoalGesture {

    /** Drags shorter than this (pixels) are clicks. */
    private static final int CLICK_SLOP_PX = 5;

    private final MapViewport viewport;
    private Point pressAt;

    GoalGesture(MapViewport viewport) {
        this.viewport = viewport;
    }

    /** The button went down at a target. */
    void press(Point at) {
        pressAt = at;
    }

    /** @return true between a press and its release */
    boolean pressed() {
        return pressAt != null;
    }

    /**
     * The button went up at {@code to}.
     *
     * @param robot the robot the goal is for (its position heads a click), or null
     * @return the goal, or null when no gesture was under way
     */
    Goal release(Point to, RobotState robot) {
        Point at = pressAt;
        pressAt = null;
        return at == null ? null : goalFor(at, to, robot);
    }

    /** @return the goal the gesture would send if released at {@code pointer}, or null when none is under way */
    Goal preview(Point pointer, RobotState robot) {
        return pressAt == null || pointer == null ? null : goalFor(pressAt, pointer, robot);
    }

    /**
     * @return the goal of a press at {@code at} released at {@code to}: the target under the press, the heading along
     *         the drag; a click without drag faces away from the robot's position ({@code robot} may be null)
     */
    Goal goalFor(Point at, Point to, RobotState robot) {
        double x = viewport.toMapX(at.x);
        double y = viewport.toMapY(at.y);
        double theta;
        if (Math.hypot(to.x - at.x, to.y - at.y) >= CLICK_SLOP_PX) {
            theta = Math.atan2(-(to.y - at.y), to.x - at.x); // screen y grows downwards
        } else {
            theta = robot != null && robot.pose() != null ? Math.atan2(y - robot.pose().pose().y(), x - robot.pose()
                    .pose().x()) : 0;
        }
        return new Goal(new Pose2D(x, y, theta), WorkspaceView.GOAL_POSITION_TOLERANCE_M,
                WorkspaceView.GOAL_HEADING_TOLERANCE_RAD);
    }
}
