package sabot.workbench.views;

import org.eclipse.swt.graphics.Point;

import sabot.controlml.payload.Goal;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.map.MapViewport;

/**
 * The operator's goal gesture on the map: press at the target, drag for the heading, release. A click without drag
 * faces away from where the robot comes from (its position for a goal, the previous target in a mission being
 * edited). Holds the press while the button is down; the view sends what {@link #release} gives, or adds it to the
 * mission ({@link MissionEditor}).
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
     * @param from where the robot comes from (a click faces away from it), or null
     * @return the goal, or null when no gesture was under way
     */
    Goal release(Point to, Point2D from) {
        Point at = pressAt;
        pressAt = null;
        return at == null ? null : goalFor(at, to, from);
    }

    /** @return the goal the gesture would give if released at {@code pointer}, or null when none is under way */
    Goal preview(Point pointer, Point2D from) {
        return pressAt == null || pointer == null ? null : goalFor(pressAt, pointer, from);
    }

    /**
     * @param from where the robot comes from, or null
     * @return the goal of a press at {@code at} released at {@code to}: the target under the press, the heading along
     *         the drag; a click without drag faces away from {@code from} (east without it)
     */
    Goal goalFor(Point at, Point to, Point2D from) {
        double x = viewport.toMapX(at.x);
        double y = viewport.toMapY(at.y);
        double theta;
        if (Math.hypot(to.x - at.x, to.y - at.y) >= CLICK_SLOP_PX) {
            theta = Math.atan2(-(to.y - at.y), to.x - at.x); // screen y grows downwards
        } else {
            theta = from != null ? Math.atan2(y - from.y(), x - from.x()) : 0;
        }
        return new Goal(new Pose2D(x, y, theta), WorkspaceView.GOAL_POSITION_TOLERANCE_M,
                WorkspaceView.GOAL_HEADING_TOLERANCE_RAD);
    }

    /** @return the robot's position in the map frame, or null when it has none (or no robot) */
    static Point2D positionOf(RobotState robot) {
        return robot == null || robot.pose() == null ? null : new Point2D(robot.pose().pose().x(), robot.pose().pose()
                .y());
    }
}
