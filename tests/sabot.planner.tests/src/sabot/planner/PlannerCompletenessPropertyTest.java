package sabot.planner;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.Random;
import java.util.function.Supplier;
import java.util.stream.Stream;

import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.Arguments;
import org.junit.jupiter.params.provider.MethodSource;

import sabot.model.geometry.Point2D;
import sabot.model.map.Costmap;

/**
 * Property-based completeness on random grids with fixed seeds: LPN finds a path exactly when the reference does,
 * every path is collision-free, N strictly decreases along it, and its cost is within 1 % of the grid optimum (plus
 * two free cells' worth, the discretisation of short paths on these small grids) or below it, and below it for most.
 */
class PlannerCompletenessPropertyTest {

    private static final int GRIDS = 400;
    private static final double COST_TOLERANCE = 1.01;
    private static final double COST_SLACK = 2 * CostModel.COST_NEUTRAL;

    /** LPN over the whole grid, stopped at the start (lpn-bounded) and focused (lpn-focused). */
    static Stream<Arguments> lpnPlanners() {
        return Stream.of(
                Arguments.of("whole grid", (Supplier<Planner>) Planners::lpn),
                Arguments.of("bounded", (Supplier<Planner>) () -> Planners.lpnBounded(CostModel.standard())),
                Arguments.of("focused", (Supplier<Planner>) () -> Planners.lpnFocused(CostModel.standard())));
    }

    @ParameterizedTest(name = "{0}")
    @MethodSource("lpnPlanners")
    void lpnFindsAPathExactlyWhenTheReferenceDoesAndEveryPathIsSafeAndDescending(String kind,
            Supplier<Planner> lpnPlanner) {
        Planner lpn = lpnPlanner.get();
        Planner reference = Planners.reference();
        int found = 0;
        int enclosed = 0;
        double worstRatio = 0;
        java.util.List<Double> ratios = new java.util.ArrayList<>();
        for (int seed = 1; seed <= GRIDS; seed++) {
            Random random = new Random(seed);
            int width = 8 + random.nextInt(50);
            int height = 8 + random.nextInt(50);
            double fill = 0.05 + 0.4 * random.nextDouble();
            Costmap costmap = TestGrids.random(seed, width, height, fill);
            Point2D start = TestGrids.randomFreePoint(random, costmap);
            Point2D goal = TestGrids.randomFreePoint(random, costmap);
            String context = "seed " + seed + " (" + width + " x " + height + ", fill " + fill + ")";

            PlanResult byReference = reference.plan(costmap, start, goal);
            PlanResult byLpn = lpn.plan(costmap, start, goal);
            assertEquals(byReference.isFound(), byLpn.isFound(), context + ": LPN and reference disagree on reachability");
            if (byLpn instanceof PlanResult.Found lpnPath) {
                found++;
                PlanResult.Found referencePath = (PlanResult.Found) byReference;
                PathChecks.assertCollisionFree(costmap, lpnPath.path(), start, goal, context + " lpn");
                PathChecks.assertCollisionFree(costmap, referencePath.path(), start, goal, context + " reference");
                PathChecks.assertDescending(lpnPath.field(), lpnPath.path(), context + " lpn");
                double ratio = lpnPath.path().cost() / referencePath.path().cost();
                worstRatio = Math.max(worstRatio, ratio);
                ratios.add(ratio);
                assertTrue(lpnPath.path().cost() <= COST_TOLERANCE * referencePath.path().cost() + COST_SLACK, context + ": LPN path costs " + lpnPath.path().cost()
                        + ", reference " + referencePath.path().cost());
            } else {
                enclosed++;
                assertEquals(UnreachableReason.GOAL_ENCLOSED, ((PlanResult.Unreachable) byLpn).reason(), context);
                assertInstanceOf(PlanResult.Unreachable.class, byReference, context);
            }
        }
        assertTrue(found > GRIDS / 4 && enclosed > GRIDS / 20, "the seeds must give both solvable (" + found
                + ") and unsolvable (" + enclosed + ") grids");
        java.util.Collections.sort(ratios);
        double median = ratios.get(ratios.size() / 2);
        assertTrue(median < 1.0, "LPN paths should mostly be cheaper than 8-connected ones; median ratio " + median);
        System.out.println("median LPN/reference cost " + median + ", ");
        lpn.close();
        System.out.println(kind + " completeness: " + found + " solvable, " + enclosed + " unsolvable, worst LPN/reference cost "
                + worstRatio);
    }
}
