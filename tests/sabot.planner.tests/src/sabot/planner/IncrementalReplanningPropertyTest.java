package sabot.planner;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.Random;

import org.junit.jupiter.api.Test;

import sabot.model.geometry.Point2D;
import sabot.model.map.CellRegion;
import sabot.model.map.Costmap;

/**
 * The incremental LPN planner repairs its navigation function after local changes; on random grids with random new
 * obstacles and cleared cells (fixed seeds) it must agree with planning from scratch on every cell's value and on
 * reachability.
 */
class IncrementalReplanningPropertyTest {

    /**
     * Bucketed propagation expands the cells of one bucket in the order they were queued, and a few updates (the
     * straight diagonal end of a triangle) depend on that order; a repair queues cells in another order than a fresh
     * computation, so values may differ by a rounding-sized amount.
     */
    private static final double TOLERANCE = 0.01;

    @Test
    void repairedNavigationFunctionEqualsARecomputedOne() {
        int compared = 0;
        double worst = 0;
        for (int seed = 1; seed <= 120; seed++) {
            Random random = new Random(seed);
            int width = 20 + random.nextInt(60);
            int height = 20 + random.nextInt(60);
            Costmap costmap = TestGrids.random(seed, width, height, 0.05 + 0.25 * random.nextDouble());
            Point2D start = TestGrids.randomFreePoint(random, costmap);
            Point2D goal = TestGrids.randomFreePoint(random, costmap);
            Planner incremental = Planners.lpnIncremental(CostModel.standard());
            incremental.plan(costmap, start, goal);
            for (int change = 0; change < 6; change++) {
                int c = random.nextInt(width - 3);
                int r = random.nextInt(height - 3);
                int size = 1 + random.nextInt(3);
                int cost = random.nextInt(3) == 0 ? random.nextInt(200) : Costmap.LETHAL;
                CellRegion block = new CellRegion(c, r, c + size - 1, r + size - 1);
                if (block.contains((int) start.x(), (int) start.y()) || block.contains((int) goal.x(), (int) goal.y())) {
                    continue;
                }
                costmap.fill(block, cost);
                PlanResult repaired = incremental.plan(costmap, start, goal);
                PlanResult fresh = Planners.lpn().plan(Costmap.of(costmap.geometry(), costmap.toArray()), start, goal);
                String context = "seed " + seed + " change " + change;
                assertEquals(fresh.isFound(), repaired.isFound(), context);
                if (fresh instanceof PlanResult.Found f && repaired instanceof PlanResult.Found g) {
                    compared++;
                    for (int row = 0; row < height; row++) {
                        for (int column = 0; column < width; column++) {
                            double expected = f.field().value(column, row);
                            double actual = g.field().value(column, row);
                            assertTrue(expected == actual || Math.abs(expected - actual) <= TOLERANCE * expected,
                                    context + ": N(" + column + ", " + row + ") is " + actual + ", recomputed " + expected);
                            if (expected != actual) {
                                worst = Math.max(worst, Math.abs(expected - actual) / expected);
                            }
                        }
                    }
                    PathChecks.assertCollisionFree(costmap, g.path(), start, goal, context);
                    PathChecks.assertDescending(g.field(), g.path(), context);
                    assertEquals(f.field().reachedCells(), g.field().reachedCells(), context);
                }
            }
        }
        assertTrue(compared > 300, "enough repaired plans compared: " + compared);
        System.out.println("incremental re-planning: " + compared + " repaired plans, worst relative difference of N " + worst);
    }
}
