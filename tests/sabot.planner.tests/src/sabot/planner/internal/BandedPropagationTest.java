package sabot.planner.internal;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.HashSet;
import java.util.List;
import java.util.Random;
import java.util.Set;

import org.junit.jupiter.api.Test;

import sabot.model.geometry.Point2D;
import sabot.model.map.CellRegion;
import sabot.model.map.Costmap;
import sabot.planner.CostModel;
import sabot.planner.PlanResult;
import sabot.planner.Planner;
import sabot.planner.Planners;
import sabot.planner.TestGrids;

/**
 * The two-thread propagation against the sequential one: the same reached cells with the same values (up to the
 * rare missed diagonal step whose outcome depends on the order within a bucket), the same bits on every run, goals on
 * band boundaries, repairs on top of it, and the helper thread's end. Small grids use bands of 2^8 cells (two to
 * eight rows) so that most cells lie near a boundary.
 */
class BandedPropagationTest {

    private static final CostModel MODEL = CostModel.standard();
    private static final int SMALL_BANDS = 8;
    /**
     * Relative difference allowed where the order within a bucket decides whether a diagonal step is seen, and in the
     * cells downstream of it (LPN's interpolation itself is within 3 % of the Euclidean cost in free space). Paths on
     * two threads meet the same properties as on one: PlannerCompletenessPropertyTest. Measured on these grids with
     * bands of four rows: 11 % of the values differ, by at most 4.9 %; with the real bands on 600 x 520, 6.6 % by at
     * most 0.54 % (2.7 % by at most 0.03 % before the cells next to a boundary were expanded last in their bucket).
     */
    private static final float ORDER_TOLERANCE = 0.1f;

    private record Computed(PlanningGrid grid, LpnNavigationFunction function) {
    }

    private static Computed compute(Costmap costmap, int threads, int[] goalCells) {
        PlanningGrid grid = new PlanningGrid();
        LpnNavigationFunction function = new LpnNavigationFunction(MODEL, threads, SMALL_BANDS, 0);
        function.gridChanged(grid, grid.sync(costmap));
        function.compute(goalCells, -1);
        return new Computed(grid, function);
    }

    /** Random passable goal cells (padded indices), one to three. */
    private static int[] goals(Random random, Costmap costmap, PlanningGrid grid) {
        int[] goals = new int[1 + random.nextInt(3)];
        for (int i = 0; i < goals.length; i++) {
            Point2D p = TestGrids.randomFreePoint(random, costmap);
            goals[i] = grid.index((int) p.x(), (int) p.y());
        }
        return goals;
    }

    private static int[] randomGoals(Costmap costmap, long seed) {
        PlanningGrid layout = new PlanningGrid();
        layout.sync(costmap);
        return goals(new Random(seed), costmap, layout);
    }

    @Test
    void twoThreadsReachTheSameCellsWithTheSameValuesAsOne() {
        int differing = 0;
        int reached = 0;
        double largest = 0;
        for (int seed = 1; seed <= 120; seed++) {
            Random random = new Random(seed);
            int width = 20 + random.nextInt(100);
            int height = 20 + random.nextInt(100);
            Costmap costmap = TestGrids.random(seed, width, height, 0.05 + 0.35 * random.nextDouble());
            PlanningGrid layout = new PlanningGrid();
            layout.sync(costmap);
            int[] goals = goals(random, costmap, layout);
            String context = "seed " + seed + " (" + width + " x " + height + ")";
            try (LpnNavigationFunction one = compute(costmap, 1, goals).function();
                    LpnNavigationFunction two = compute(costmap, 2, goals).function()) {
                assertEquals(one.finalizedCount(), two.finalizedCount(), context + ": cells reached");
                int[] expected = one.potential();
                int[] actual = two.potential();
                for (int cell = 0; cell < expected.length; cell++) {
                    assertEquals(one.isReached(cell), two.isReached(cell), context + ": cell " + cell + " reached");
                    if (expected[cell] != actual[cell]) {
                        float a = LpnNavigationFunction.decode(expected[cell]);
                        float b = LpnNavigationFunction.decode(actual[cell]);
                        assertTrue(Math.abs(a - b) <= ORDER_TOLERANCE * a, context + ": cell " + cell + " one thread "
                                + a + ", two " + b);
                        largest = Math.max(largest, Math.abs(a - b) / a);
                        differing++;
                    }
                }
                reached += one.finalizedCount();
            }
        }
        assertTrue(reached > 100_000, "the grids must be large enough to mean something: " + reached);
        System.out.printf("two threads vs one: %d of %d values differ, by at most %.2e (relative)%n", differing, reached,
                largest);
        assertTrue(differing < reached / 8, differing + " of " + reached + " values differ");
    }

    @Test
    void everyRunGivesTheSameBits() {
        Costmap costmap = TestGrids.random(42, 150, 110, 0.2);
        int[] goals = randomGoals(costmap, 42);
        Computed first = compute(costmap, 2, goals);
        int[] bits = first.function().potential().clone();
        for (int run = 0; run < 20; run++) {
            first.function().compute(goals, -1);
            assertArrayEquals(bits, first.function().potential(), "run " + run + " of the same instance");
        }
        try (LpnNavigationFunction fresh = compute(costmap, 2, goals).function()) {
            assertArrayEquals(bits, fresh.potential(), "a fresh instance");
        }
        first.function().close();
    }

    @Test
    void goalsOnEveryBandBoundaryAndInBothBands() {
        Costmap costmap = TestGrids.free(100, 60);
        PlanningGrid layout = new PlanningGrid();
        layout.sync(costmap);
        // the first and last cells of every band, wherever they are passable grid cells
        List<Integer> boundary = new java.util.ArrayList<>();
        for (int start = 1 << SMALL_BANDS; start < layout.paddedSize(); start += 1 << SMALL_BANDS) {
            for (int cell : new int[] { start - 1, start }) {
                int column = cell % layout.stride() - 1;
                int row = cell / layout.stride() - 1;
                if (column >= 0 && column < 100 && row >= 0 && row < 60) {
                    boundary.add(cell);
                }
            }
        }
        assertTrue(boundary.size() > 20);
        for (int i = 0; i < boundary.size(); i += 3) {
            int[] goals = i + 1 < boundary.size() ? new int[] { boundary.get(i), boundary.get(i + 1) }
                    : new int[] { boundary.get(i) };
            try (LpnNavigationFunction one = compute(costmap, 1, goals).function();
                    LpnNavigationFunction two = compute(costmap, 2, goals).function()) {
                assertEquals(100 * 60, two.finalizedCount());
                for (int goal : goals) {
                    assertEquals(0f, LpnNavigationFunction.decode(two.potential()[goal]));
                }
                for (int cell = 0; cell < layout.paddedSize(); cell++) {
                    float a = LpnNavigationFunction.decode(one.potential()[cell]);
                    float b = LpnNavigationFunction.decode(two.potential()[cell]);
                    assertTrue(a == b || Math.abs(a - b) <= ORDER_TOLERANCE * a, "goals at " + List.of(goals[0])
                            + ": cell " + cell + " " + a + " vs " + b);
                }
            }
        }
    }

    @Test
    void oneFunctionServesGridsOfAnyWidthInTurn() {
        try (LpnNavigationFunction two = new LpnNavigationFunction(MODEL, 2, SMALL_BANDS, 0)) {
            for (int width : new int[] { 30, 400, 30 }) {
                Costmap costmap = TestGrids.random(width, width, 40, 0.1);
                PlanningGrid grid = new PlanningGrid();
                two.gridChanged(grid, grid.sync(costmap));
                int[] goals = randomGoals(costmap, width);
                two.compute(goals, -1);
                try (LpnNavigationFunction one = compute(costmap, 1, goals).function()) {
                    assertEquals(one.finalizedCount(), two.finalizedCount(), width + " wide");
                }
            }
        }
    }

    @Test
    void anEnclosedGoalReachesItsEnclosureOnly() {
        Costmap costmap = TestGrids.free(90, 90);
        for (int i = 30; i <= 50; i++) {
            costmap.set(i, 30, Costmap.LETHAL);
            costmap.set(i, 50, Costmap.LETHAL);
            costmap.set(30, i, Costmap.LETHAL);
            costmap.set(50, i, Costmap.LETHAL);
        }
        PlanningGrid layout = new PlanningGrid();
        layout.sync(costmap);
        try (LpnNavigationFunction two = compute(costmap, 2, new int[] { layout.index(40, 40) }).function()) {
            assertEquals(19 * 19, two.finalizedCount());
            assertFalse(two.isReached(layout.index(10, 10)));
        }
    }

    @Test
    void aRepairAfterATwoThreadComputationMatchesAFreshOne() {
        Costmap costmap = TestGrids.random(9, 120, 100, 0.15);
        int[] goals = randomGoals(costmap, 9);
        Computed computed = compute(costmap, 2, goals);
        // a new obstacle near the middle, as a sonar would add it
        CellRegion block = new CellRegion(55, 45, 60, 52);
        costmap.fill(block, Costmap.LETHAL);
        CellRegion changed = computed.grid().sync(costmap);
        try (LpnNavigationFunction two = computed.function();
                LpnNavigationFunction fresh = compute(costmap, 1, goals).function()) {
            assertTrue(two.repair(computed.grid(), changed, goals), "a rise in cost is repaired");
            for (int cell = 0; cell < computed.grid().paddedSize(); cell++) {
                assertEquals(fresh.isReached(cell), two.isReached(cell), "cell " + cell);
                float a = LpnNavigationFunction.decode(fresh.potential()[cell]);
                float b = LpnNavigationFunction.decode(two.potential()[cell]);
                assertTrue(a == b || Math.abs(a - b) <= ORDER_TOLERANCE * a, "cell " + cell + " " + a + " vs " + b);
            }
        }
    }

    @Test
    void closeEndsTheHelperThreadAndAClosedFunctionRefusesWork() throws InterruptedException {
        Set<Thread> before = new HashSet<>(Thread.getAllStackTraces().keySet());
        Costmap costmap = TestGrids.free(40, 40);
        PlanningGrid layout = new PlanningGrid();
        layout.sync(costmap);
        Computed computed = compute(costmap, 2, new int[] { layout.index(5, 5) });
        Thread helper = Thread.getAllStackTraces().keySet().stream().filter(t -> !before.contains(t)
                && t.getName().equals("sabot-lpn-band-worker")).findFirst().orElseThrow();
        assertTrue(helper.isDaemon());
        computed.function().close();
        helper.join(10_000);
        assertFalse(helper.isAlive(), "the helper thread ends on close");
        // closing again is harmless; computing again starts a new helper (the function stays usable)
        computed.function().close();
        computed.function().compute(new int[] { layout.index(5, 5) }, -1);
        assertEquals(40 * 40, computed.function().finalizedCount());
        computed.function().close();
    }

    @Test
    void threadsAreOneOrTwo() {
        assertThrows(IllegalArgumentException.class, () -> new LpnNavigationFunction(MODEL, 0));
        assertThrows(IllegalArgumentException.class, () -> new LpnNavigationFunction(MODEL, 3));
        assertThrows(IllegalArgumentException.class, () -> Planners.lpn(MODEL, 3));
        assertThrows(IllegalArgumentException.class, () -> Planners.byName("lpn", MODEL, 0));
    }

    @Test
    void withTheRealBandsAlmostAllValuesAreTheSame() {
        Costmap costmap = TestGrids.random(5, 600, 520, 0.15);
        PlanningGrid grid = new PlanningGrid();
        CellRegion all = grid.sync(costmap);
        int[] goals = goals(new Random(5), costmap, grid);
        try (LpnNavigationFunction one = new LpnNavigationFunction(MODEL, 1);
                LpnNavigationFunction two = new LpnNavigationFunction(MODEL, 2)) {
            one.gridChanged(grid, all);
            two.gridChanged(grid, all);
            one.compute(goals, -1);
            two.compute(goals, -1);
            assertEquals(one.finalizedCount(), two.finalizedCount());
            int differing = 0;
            double largest = 0;
            for (int cell = 0; cell < grid.paddedSize(); cell++) {
                assertEquals(one.isReached(cell), two.isReached(cell), "cell " + cell);
                if (one.potential()[cell] != two.potential()[cell]) {
                    float a = LpnNavigationFunction.decode(one.potential()[cell]);
                    largest = Math.max(largest, Math.abs(a - LpnNavigationFunction.decode(two.potential()[cell])) / a);
                    differing++;
                }
            }
            System.out.printf("two threads vs one, 600 x 520: %d of %d values differ, by at most %.2e%n", differing,
                    one.finalizedCount(), largest);
            assertTrue(differing < one.finalizedCount() / 10, differing + " values differ");
            assertTrue(largest < 1e-2, "largest relative difference " + largest);
        }
    }

    @Test
    void twoThreadPlannerOnALargeGridGivesTheSamePath() {
        Costmap costmap = TestGrids.random(5, 600, 520, 0.15);
        Random random = new Random(5);
        try (Planner one = Planners.lpn(MODEL); Planner two = Planners.lpn(MODEL, 2)) {
            for (int i = 0; i < 5; i++) {
                Point2D start = TestGrids.randomFreePoint(random, costmap);
                Point2D goal = TestGrids.randomFreePoint(random, costmap);
                PlanResult a = one.plan(costmap, start, goal);
                PlanResult b = two.plan(costmap, start, goal);
                assertEquals(a.isFound(), b.isFound(), "plan " + i);
                if (a instanceof PlanResult.Found fa) {
                    PlanResult.Found fb = assertInstanceOf(PlanResult.Found.class, b);
                    assertEquals(fa.field().reachedCells(), fb.field().reachedCells(), "plan " + i);
                    assertEquals(fa.path().cost(), fb.path().cost(), 1e-3 * fa.path().cost(), "plan " + i);
                }
            }
        }
    }
}
