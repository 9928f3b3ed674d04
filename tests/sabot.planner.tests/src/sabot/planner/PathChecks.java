package sabot.planner;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;

import sabot.model.geometry.Point2D;
import sabot.model.map.Costmap;

/** Assertions every planned path must satisfy. */
final class PathChecks {

    private PathChecks() {
    }

    /** Starts at the start, ends at the goal, and every segment crosses only passable cells. */
    static void assertCollisionFree(Costmap costmap, PlannedPath path, Point2D start, Point2D goal, String context) {
        List<Point2D> w = path.waypoints();
        assertEquals(start, w.get(0), context + ": path must start at the start");
        assertEquals(goal, w.get(w.size() - 1), context + ": path must end at the goal");
        double cost = CostModel.standard().pathCost(costmap, w);
        assertTrue(cost < Double.POSITIVE_INFINITY, context + ": path crosses a lethal, inscribed or unknown cell");
        assertEquals(cost, path.cost(), 1e-6 * Math.max(1, cost), context + ": reported cost is the line integral");
    }

    /** N strictly decreases from waypoint to waypoint until the goal set (N = 0) is entered. */
    static void assertDescending(PotentialField field, PlannedPath path, String context) {
        double previous = Double.POSITIVE_INFINITY;
        for (int i = 0; i < path.waypoints().size(); i++) {
            double value = field.valueAt(path.waypoints().get(i));
            assertTrue(value < Double.POSITIVE_INFINITY, context + ": waypoint " + i + " has no navigation value");
            if (previous == 0) {
                assertEquals(0, value, context + ": after entering the goal cell the path stays there");
            } else {
                assertTrue(value < previous, context + ": N does not decrease at waypoint " + i + " (" + previous
                        + " -> " + value + ")");
            }
            previous = value;
        }
        assertEquals(0, previous, context + ": path must end in the goal set");
    }
}
