package sabot.planner;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

import sabot.model.geometry.Point2D;
import sabot.model.map.Costmap;

/** The navigation function's values and the shape of the paths descending it. */
class LpnNavigationFunctionTest {

    @Test
    void freeSpaceValuesApproachEuclideanDistanceInEveryDirection() {
        Costmap costmap = TestGrids.free(101, 101);
        Point2D goal = new Point2D(50.5, 50.5);
        PlanResult.Found found = assertInstanceOf(PlanResult.Found.class,
                Planners.lpn().plan(costmap, new Point2D(0.5, 0.5), goal));
        PotentialField field = found.field();
        for (double angle = 0; angle < 2 * Math.PI; angle += Math.PI / 16) {
            int column = 50 + (int) Math.round(40 * Math.cos(angle));
            int row = 50 + (int) Math.round(40 * Math.sin(angle));
            double euclidean = Math.hypot(column - 50, row - 50) * CostModel.COST_NEUTRAL;
            double value = field.value(column, row);
            assertTrue(value >= euclidean * 0.999 && value <= euclidean * 1.03,
                    "N at angle " + angle + " is " + value + ", Euclidean cost " + euclidean);
        }
    }

    @Test
    void freeSpacePathIsNearlyStraightAtAnAngleNoGridDirectionHas() {
        Costmap costmap = TestGrids.free(120, 60);
        Point2D start = new Point2D(2.5, 2.5);
        Point2D goal = new Point2D(110.5, 40.5);
        PlanResult.Found found = assertInstanceOf(PlanResult.Found.class, Planners.lpn().plan(costmap, start, goal));
        double straight = start.distanceTo(goal);
        assertTrue(found.path().length() < straight * 1.005, "length " + found.path().length() + " vs " + straight);
        PlanResult.Found reference = assertInstanceOf(PlanResult.Found.class,
                Planners.reference().plan(costmap, start, goal));
        assertTrue(reference.path().length() > straight * 1.03, "the 8-connected path is tied to grid directions");
    }

    @Test
    void gradedCostBendsThePathAroundExpensiveCells() {
        Costmap costmap = TestGrids.free(60, 30);
        costmap.fill(new sabot.model.map.CellRegion(25, 8, 35, 22), 200);
        Point2D start = new Point2D(5.5, 15.5);
        Point2D goal = new Point2D(55.5, 15.5);
        PlanResult.Found found = assertInstanceOf(PlanResult.Found.class, Planners.lpn().plan(costmap, start, goal));
        for (Point2D p : found.path().waypoints()) {
            assertTrue(p.x() < 25 || p.x() > 36 || p.y() < 8 || p.y() > 23,
                    "path should go around the costly block, passes " + p);
        }
        PathChecks.assertDescending(found.field(), found.path(), "graded");
    }

    @Test
    void boundedPlannerGivesTheSamePathOverFewerCells() {
        Costmap costmap = TestGrids.random(7, 200, 200, 0.2);
        java.util.Random random = new java.util.Random(7);
        Point2D start = TestGrids.randomFreePoint(random, costmap);
        Point2D goal = TestGrids.randomFreePoint(random, costmap);
        PlanResult full = Planners.lpn().plan(costmap, start, goal);
        PlanResult bounded = Planners.lpnBounded(CostModel.standard()).plan(costmap, start, goal);
        assertEquals(full.isFound(), bounded.isFound());
        if (full instanceof PlanResult.Found f && bounded instanceof PlanResult.Found b) {
            assertEquals(f.path().cost(), b.path().cost(), 1e-6 * f.path().cost());
            assertTrue(b.field().reachedCells() <= f.field().reachedCells());
        }
    }

    /**
     * A planner reused for many requests answers each exactly as a fresh one: the reset between computations (a list
     * of the cells a small computation reached, popped or still queued when a bounded one stops; a whole copy of the
     * initial values after a large one) leaves no value behind. Requests alternate near and far goals so that both
     * resets occur, on every LPN planner.
     */
    @Test
    void aReusedPlannerAnswersEveryRequestAsAFreshOne() {
        Costmap costmap = TestGrids.random(11, 160, 120, 0.2);
        java.util.Random random = new java.util.Random(11);
        for (String name : java.util.List.of("lpn", "lpn-bounded", "lpn-focused", "lpn-incremental")) {
            Planner reused = Planners.byName(name, CostModel.standard()).orElseThrow();
            int found = 0;
            for (int i = 0; i < 40; i++) {
                Point2D start = TestGrids.randomFreePoint(random, costmap);
                Point2D goal = i % 2 == 0 ? TestGrids.randomFreePoint(random, costmap)
                        : new Point2D(Math.min(159.5, start.x() + 3), start.y());
                PlanResult again = reused.plan(costmap, start, goal);
                PlanResult fresh = Planners.byName(name, CostModel.standard()).orElseThrow().plan(costmap, start, goal);
                assertEquals(fresh.isFound(), again.isFound(), name + " request " + i);
                if (fresh instanceof PlanResult.Found f && again instanceof PlanResult.Found a) {
                    found++;
                    assertEquals(f.path().cost(), a.path().cost(), 0, name + " request " + i);
                    assertEquals(f.field().reachedCells(), a.field().reachedCells(), name + " request " + i);
                }
            }
            assertTrue(found >= 10, name + ": only " + found + " requests had a path");
        }
    }
}
