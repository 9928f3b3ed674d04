package sabot.planner;

import java.util.List;

import sabot.model.geometry.Point2D;

/**
 * A collision-free polyline from the start to a goal.
 *
 * @param waypoints map-frame points in metres, first the start, last the goal; at least two (start and goal may
 *                  coincide)
 * @param length    Euclidean length of the polyline in metres
 * @param cost      line integral of the cell cost density along the polyline ({@link CostModel#pathCost}), in navfn
 *                  cost units; the quantity the planners minimise
 */
public record PlannedPath(List<Point2D> waypoints, double length, double cost) {

    public PlannedPath {
        waypoints = List.copyOf(waypoints);
        if (waypoints.size() < 2) {
            throw new IllegalArgumentException("a path has at least a start and a goal waypoint");
        }
    }

    /** @return the first waypoint */
    public Point2D start() {
        return waypoints.get(0);
    }

    /** @return the last waypoint */
    public Point2D end() {
        return waypoints.get(waypoints.size() - 1);
    }
}
