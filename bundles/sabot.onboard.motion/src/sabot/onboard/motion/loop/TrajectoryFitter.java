package sabot.onboard.motion.loop;

import java.util.ArrayList;
import java.util.List;

import sabot.control.MotionLimits;
import sabot.control.trajectory.InvalidPathException;
import sabot.control.trajectory.SplineTrajectory;
import sabot.model.geometry.Point2D;

/** Turns a planner's path (cell by cell) into a trajectory the tracker can follow within the motion limits. */
final class TrajectoryFitter {

    /** Spacing of the waypoints the spline is fitted through, m (planner paths come cell by cell). */
    static final double WAYPOINT_SPACING = 0.3;

    private TrajectoryFitter() {
    }

    /**
     * @param path     the planner's path
     * @param start    where the robot stands (exactly)
     * @param goal     the goal's position (exactly)
     * @param planning the limits a trajectory is planned with (the motion limits less the feedback's headroom)
     * @return a curvature-limited spline trajectory through the thinned path; no trajectory (and no refusal) when the
     *         robot already stands on the goal's position
     */
    static ControlLoop.Plan fit(List<Point2D> path, Point2D start, Point2D goal, MotionLimits planning) {
        return spline(thin(path, start, goal), planning);
    }

    /**
     * One trajectory through several planned segments, each ending exactly on its end point (the pass targets, then
     * the goal): the robot drives through the ends without stopping.
     *
     * @param segments the planner's path of each segment, in order
     * @param start    where the robot stands (exactly)
     * @param ends     each segment's end (exactly), as many as segments
     * @param planning the limits a trajectory is planned with
     */
    static ControlLoop.Plan fit(List<List<Point2D>> segments, Point2D start, List<Point2D> ends,
            MotionLimits planning) {
        if (segments.size() == 1) {
            return fit(segments.get(0), start, ends.get(0), planning);
        }
        List<Point2D> waypoints = new ArrayList<>();
        Point2D from = start;
        for (int i = 0; i < segments.size(); i++) {
            List<Point2D> part = thin(segments.get(i), from, ends.get(i));
            waypoints.addAll(waypoints.isEmpty() ? part : part.subList(1, part.size()));
            from = ends.get(i);
        }
        return spline(waypoints, planning);
    }

    private static ControlLoop.Plan spline(List<Point2D> waypoints, MotionLimits planning) {
        if (waypoints.size() < 2) {
            return new ControlLoop.Plan(null, 0, null);
        }
        try {
            SplineTrajectory t = SplineTrajectory.planCurvatureLimited(waypoints, planning.maxLinearSpeed(), planning);
            return new ControlLoop.Plan(t, t.length(), null);
        } catch (InvalidPathException e) {
            return new ControlLoop.Plan(null, 0, "no trajectory through the path: " + e.getMessage());
        }
    }

    /** Keeps a waypoint every {@link #WAYPOINT_SPACING} m, the exact start and the exact goal. */
    static List<Point2D> thin(List<Point2D> path, Point2D start, Point2D goal) {
        List<Point2D> out = new ArrayList<>();
        out.add(start);
        Point2D last = start;
        for (int i = 1; i < path.size() - 1; i++) {
            Point2D p = path.get(i);
            if (Math.hypot(p.x() - last.x(), p.y() - last.y()) >= WAYPOINT_SPACING
                    && Math.hypot(p.x() - goal.x(), p.y() - goal.y()) >= WAYPOINT_SPACING / 2) {
                out.add(p);
                last = p;
            }
        }
        if (Math.hypot(goal.x() - start.x(), goal.y() - start.y()) > 1e-3) {
            out.add(goal);
        }
        return out;
    }
}
