package sabot.planner;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.Random;

import org.junit.jupiter.api.Test;

import sabot.model.geometry.Point2D;
import sabot.model.map.Costmap;

/**
 * {@code lpn-focused} against the exhaustive propagation ({@code lpn}): the same answer, a value at the start and a
 * path cost no higher (order effects aside), over no more cells; enclosed goals and starts are still reported, and a
 * detour longer than the first bound allows is found by the next attempt.
 */
class FocusedPlanningTest {

    private static final int GRIDS = 300;
    /**
     * How much higher the focused N(start) and path cost may be than the exhaustive ones: the order of expansion
     * inside a bucket changes which diagonal steps the interpolated update takes (the class comment of
     * LpnNavigationFunction); measured worst case below 0.1 %.
     */
    private static final double TOLERANCE = 2e-3;
    /**
     * How much lower the focused N(start) may be: the same order effects, in the other direction (seed 54: 0.7 %
     * lower, with a path 0.9 % cheaper than the exhaustive propagation's); a larger gap would be a value below the
     * cost of any path.
     */
    private static final double LOWER_TOLERANCE = 2e-2;

    @Test
    void focusedPlansMatchTheExhaustivePropagationOverNoMoreCells() {
        try (Planner exhaustive = Planners.lpn(CostModel.standard());
                Planner focused = Planners.lpnFocused(CostModel.standard())) {
            int found = 0;
            int fewer = 0;
            double worstCost = 0;
            double worstValue = 0;
            for (int seed = 1; seed <= GRIDS; seed++) {
                Random random = new Random(seed);
                int width = 20 + random.nextInt(120);
                int height = 20 + random.nextInt(120);
                Costmap costmap = TestGrids.random(seed, width, height, 0.05 + 0.3 * random.nextDouble());
                Point2D start = TestGrids.randomFreePoint(random, costmap);
                Point2D goal = TestGrids.randomFreePoint(random, costmap);
                String context = "seed " + seed + " (" + width + " x " + height + ")";
                PlanResult all = exhaustive.plan(costmap, start, goal);
                PlanResult some = focused.plan(costmap, start, goal);
                assertEquals(all.isFound(), some.isFound(), context);
                if (all instanceof PlanResult.Found a && some instanceof PlanResult.Found f) {
                    found++;
                    double startValueAll = a.field().valueAt(start);
                    double startValueSome = f.field().valueAt(start);
                    assertTrue(startValueSome <= (1 + TOLERANCE) * startValueAll + 1e-3
                            && startValueSome >= (1 - LOWER_TOLERANCE) * startValueAll, context + ": N(start) "
                                    + startValueSome + ", exhaustive " + startValueAll);
                    assertTrue(f.path().cost() <= (1 + TOLERANCE) * a.path().cost(), context + ": path cost "
                            + f.path().cost() + ", exhaustive " + a.path().cost());
                    worstCost = Math.max(worstCost, f.path().cost() / a.path().cost());
                    worstValue = Math.max(worstValue, startValueSome / startValueAll - 1);
                    PathChecks.assertCollisionFree(costmap, f.path(), start, goal, context);
                    PathChecks.assertDescending(f.field(), f.path(), context);
                    assertTrue(f.field().reachedCells() <= a.field().reachedCells(), context);
                    if (f.field().reachedCells() < a.field().reachedCells()) {
                        fewer++;
                    }
                } else {
                    assertEquals(((PlanResult.Unreachable) all).reason(), ((PlanResult.Unreachable) some).reason(),
                            context);
                }
            }
            System.out.println("lpn-focused: worst path cost ratio to lpn " + worstCost + ", worst N(start) excess "
                    + worstValue + ", fewer cells on " + fewer + " of " + found);
            assertTrue(found > GRIDS / 2, "most seeds must give solvable grids: " + found);
            assertTrue(fewer > found / 2, "the focus must spare cells on most grids: " + fewer + " of " + found);
        }
    }

    @Test
    void aDetourBeyondTheFirstBoundIsFoundByTheNextAttempt() {
        // a wall between start and goal, open at the far end: the path is about three times the straight distance,
        // beyond the first bound (5 % over it), so the first attempt defers cells and fails
        Costmap costmap = TestGrids.free(60, 60);
        for (int row = 0; row < 55; row++) {
            costmap.set(30, row, Costmap.LETHAL);
        }
        Point2D start = costmap.geometry().cellCentre(20, 5);
        Point2D goal = costmap.geometry().cellCentre(40, 5);
        try (Planner exhaustive = Planners.lpn(CostModel.standard());
                Planner focused = Planners.lpnFocused(CostModel.standard())) {
            PlanResult.Found all = assertInstanceOf(PlanResult.Found.class, exhaustive.plan(costmap, start, goal));
            PlanResult.Found some = assertInstanceOf(PlanResult.Found.class, focused.plan(costmap, start, goal));
            assertTrue(all.path().length() > 2.5 * start.distanceTo(goal), "the wall forces a detour");
            double startValue = all.field().valueAt(start);
            assertEquals(startValue, some.field().valueAt(start), TOLERANCE * startValue);
            assertTrue(some.path().cost() <= (1 + TOLERANCE) * all.path().cost());
            PathChecks.assertCollisionFree(costmap, some.path(), start, goal, "detour");
            PathChecks.assertDescending(some.field(), some.path(), "detour");
        }
    }

    @Test
    void mazePlansBoundByLandmarksMatchTheExhaustivePropagationOverFewerCells() {
        // paths many times the straight line: the first plan's straight-line bound is poor, so the next plans on
        // the same grid are bounded by landmarks, also after a new obstacle (a rise keeps them) and after it is
        // cleared again (a fall drops them)
        Costmap costmap = TestGrids.maze(17, 30, true);
        Point2D corner = costmap.geometry().cellCentre(2, 2);
        Point2D opposite = costmap.geometry().cellCentre(costmap.width() - 3, costmap.height() - 3);
        Random random = new Random(17);
        try (Planner exhaustive = Planners.lpn(CostModel.standard());
                Planner focused = Planners.lpnFocused(CostModel.standard())) {
            PlanResult.Found straightLine = assertMatches(exhaustive, focused, costmap, corner, opposite, "first plan");
            PlanResult.Found byLandmarks = assertMatches(exhaustive, focused, costmap, corner, opposite, "re-plan");
            assertTrue(byLandmarks.field().reachedCells() < straightLine.field().reachedCells() * 3 / 4,
                    "landmarks: " + byLandmarks.field().reachedCells() + " cells, straight line: "
                            + straightLine.field().reachedCells());
            for (int i = 0; i < 40; i++) {
                Point2D start = TestGrids.randomFreePoint(random, costmap);
                Point2D goal = TestGrids.randomFreePoint(random, costmap);
                assertMatches(exhaustive, focused, costmap, start, goal, "pair " + i);
            }
            PlanResult.Found before = assertMatches(exhaustive, focused, costmap, corner, opposite, "before");
            int column = (int) byLandmarks.path().waypoints().get(byLandmarks.path().waypoints().size() / 2).x();
            int row = (int) byLandmarks.path().waypoints().get(byLandmarks.path().waypoints().size() / 2).y();
            int previous = costmap.cost(column, row);
            costmap.set(column, row, Costmap.MAX_GRADED);
            PlanResult.Found risen = assertMatches(exhaustive, focused, costmap, corner, opposite, "cost risen");
            assertTrue(risen.field().reachedCells() < straightLine.field().reachedCells() * 3 / 4,
                    "a rise keeps the landmarks: " + risen.field().reachedCells() + " cells");
            // a goal walled in by new obstacles (a rise: the landmarks stay) is reported as without them
            Point2D walledIn = byLandmarks.path().waypoints().get(byLandmarks.path().waypoints().size() / 3);
            int wc = (int) walledIn.x();
            int wr = (int) walledIn.y();
            int[] before8 = new int[9];
            for (int k = 0; k < 9; k++) {
                before8[k] = costmap.cost(wc - 1 + k % 3, wr - 1 + k / 3);
                if (k != 4) {
                    costmap.set(wc - 1 + k % 3, wr - 1 + k / 3, Costmap.LETHAL);
                }
            }
            Point2D inside = costmap.geometry().cellCentre(wc, wr);
            for (Point2D[] pair : new Point2D[][] {{corner, inside}, {inside, opposite}}) {
                PlanResult all = exhaustive.plan(costmap, pair[0], pair[1]);
                PlanResult some = focused.plan(costmap, pair[0], pair[1]);
                assertEquals(UnreachableReason.GOAL_ENCLOSED, assertInstanceOf(PlanResult.Unreachable.class, all).reason());
                assertEquals(UnreachableReason.GOAL_ENCLOSED, assertInstanceOf(PlanResult.Unreachable.class, some).reason());
            }
            for (int k = 0; k < 9; k++) {
                costmap.set(wc - 1 + k % 3, wr - 1 + k / 3, before8[k]);
            }
            costmap.set(column, row, previous);
            PlanResult.Found fallen = assertMatches(exhaustive, focused, costmap, corner, opposite, "cost fallen");
            assertEquals(before.path().cost(), fallen.path().cost(), TOLERANCE * before.path().cost());
        }
    }

    /** Plans with both planners and checks the focused answer against the exhaustive one; returns the focused plan. */
    private static PlanResult.Found assertMatches(Planner exhaustive, Planner focused, Costmap costmap, Point2D start,
            Point2D goal, String context) {
        PlanResult.Found all = assertInstanceOf(PlanResult.Found.class, exhaustive.plan(costmap, start, goal), context);
        PlanResult.Found some = assertInstanceOf(PlanResult.Found.class, focused.plan(costmap, start, goal), context);
        double startValueAll = all.field().valueAt(start);
        double startValueSome = some.field().valueAt(start);
        assertTrue(startValueSome <= (1 + TOLERANCE) * startValueAll + 1e-3
                && startValueSome >= (1 - LOWER_TOLERANCE) * startValueAll,
                context + ": N(start) " + startValueSome + ", exhaustive " + startValueAll);
        assertTrue(some.path().cost() <= (1 + TOLERANCE) * all.path().cost(),
                context + ": path cost " + some.path().cost() + ", exhaustive " + all.path().cost());
        PathChecks.assertCollisionFree(costmap, some.path(), start, goal, context);
        PathChecks.assertDescending(some.field(), some.path(), context);
        assertTrue(some.field().reachedCells() <= all.field().reachedCells(), context);
        return some;
    }

    @Test
    void anEnclosedGoalOrStartIsReported() {
        Costmap costmap = TestGrids.free(60, 60);
        for (int i = 20; i <= 30; i++) {
            costmap.set(i, 20, Costmap.LETHAL);
            costmap.set(i, 30, Costmap.LETHAL);
            costmap.set(20, i, Costmap.LETHAL);
            costmap.set(30, i, Costmap.LETHAL);
        }
        Point2D inside = costmap.geometry().cellCentre(25, 25);
        Point2D outside = costmap.geometry().cellCentre(5, 50);
        try (Planner focused = Planners.lpnFocused(CostModel.standard())) {
            PlanResult toInside = focused.plan(costmap, outside, inside);
            assertEquals(UnreachableReason.GOAL_ENCLOSED,
                    assertInstanceOf(PlanResult.Unreachable.class, toInside).reason());
            PlanResult fromInside = focused.plan(costmap, inside, outside);
            assertEquals(UnreachableReason.GOAL_ENCLOSED,
                    assertInstanceOf(PlanResult.Unreachable.class, fromInside).reason());
            PlanResult within = focused.plan(costmap, inside, costmap.geometry().cellCentre(27, 23));
            assertInstanceOf(PlanResult.Found.class, within);
        }
    }
}
