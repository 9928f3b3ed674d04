package sabot.planner.internal;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;
import java.util.Random;

import org.junit.jupiter.api.Test;

import sabot.model.map.CellRegion;
import sabot.model.map.Costmap;
import sabot.planner.CostModel;
import sabot.planner.TestGrids;

/**
 * The shortcut pass decides by the closed form of a free box only where the traversal's sums would decide the same
 * ({@link GradientDescent.FreeBoxes}), so the path is the same point for point; and the free runs it reads
 * ({@link PlanningGrid#freeRuns}) follow the grid's changes.
 */
class GradientDescentTest {

    private static final CostModel MODEL = CostModel.standard();

    @Test
    void theClosedFormOfAFreeBoxDiffersFromTheTraversalFarBelowTheDecisiveFraction() {
        PlanningGrid grid = new PlanningGrid();
        grid.sync(TestGrids.free(40, 40));
        GradientDescent.FreeBoxes boxes = new GradientDescent.FreeBoxes(grid, MODEL.densityTable());
        GridTraversal.PaddedDensity cells = new GridTraversal.PaddedDensity(grid, MODEL.densityTable());
        Random random = new Random(20261128);
        double worst = 0;
        for (int i = 0; i < 200_000; i++) {
            // any direction, on cell borders and corners as well as inside cells (a descent's fallback steps end at
            // centres, its goal and start anywhere), up to the longest shortcut the pass tries
            double x0 = 12 + pick(random);
            double y0 = 12 + pick(random);
            double angle = i % 8 == 0 ? Math.PI / 4 * random.nextInt(8) : 2 * Math.PI * random.nextDouble();
            double length = GradientDescent.MAX_SHORTCUT * random.nextDouble();
            double x1 = x0 + length * Math.cos(angle);
            double y1 = y0 + length * Math.sin(angle);
            double closed = boxes.integral(x0, y0, x1, y1);
            double walked = GridTraversal.integrate(x0, y0, x1, y1, cells);
            if (Double.isNaN(closed)) {
                assertTrue(length < 1e-6, "only a segment too short for the closed form has none here");
                continue;
            }
            worst = Math.max(worst, Math.abs(closed - walked) / walked);
        }
        assertTrue(worst < GradientDescent.FreeBoxes.DECISIVE / 100, "largest relative difference " + worst);
    }

    @Test
    void aBoxWithACellThatIsNotFreeHasNoClosedForm() {
        Costmap costmap = TestGrids.free(20, 20);
        costmap.set(10, 5, 1);
        costmap.set(3, 14, Costmap.LETHAL);
        PlanningGrid grid = new PlanningGrid();
        grid.sync(costmap);
        GradientDescent.FreeBoxes boxes = new GradientDescent.FreeBoxes(grid, MODEL.densityTable());
        float free = MODEL.densityTable()[Costmap.FREE];
        assertTrue(Double.isNaN(boxes.integral(8.5, 4.5, 12.5, 6.5)), "graded cell inside the box");
        assertTrue(Double.isNaN(boxes.integral(12.5, 6.5, 8.5, 4.5)), "the same box from its other corner");
        assertTrue(Double.isNaN(boxes.integral(10.2, 0.5, 10.7, 19.5)), "graded cell in the box's one column");
        assertTrue(Double.isNaN(boxes.integral(7.5, 5.5, 10.5, 4.5)), "graded cell in the box's last column");
        assertTrue(Double.isNaN(boxes.integral(0.5, 18.5, 4.5, 12.5)), "lethal cell inside the box");
        assertEquals(5 * free, boxes.integral(8.5, 6.5, 11.5, 10.5), 1e-12, "the box just below the graded cell");
        assertEquals(Math.sqrt(2) * free, boxes.integral(19.0, 19.0, 18.0, 18.0), 1e-12, "at the grid's corner");
        assertTrue(Double.isNaN(boxes.integral(19.5, 19.5, 20.5, 19.5)), "a point outside the grid");
        assertTrue(Double.isNaN(boxes.integral(0.5, 0.5, -0.5, 0.5)), "a point outside the grid");
    }

    @Test
    void pathsAreTheSamePointForPointWithAndWithoutTheClosedForm() {
        int compared = 0;
        for (long seed = 1; seed <= 24; seed++) {
            Costmap costmap = switch ((int) (seed % 3)) {
                case 0 -> TestGrids.maze(seed, 10, true);
                case 1 -> TestGrids.random(seed, 120, 90, 0.15);
                default -> rectangles(seed, 150, 110, 0.2);
            };
            PlanningGrid grid = new PlanningGrid();
            CellRegion changed = grid.sync(costmap);
            LpnNavigationFunction function = new LpnNavigationFunction(MODEL);
            function.gridChanged(grid, changed);
            Random random = new Random(seed);
            for (int goal = 0; goal < 3; goal++) {
                PlanRequest request = PlanRequest.resolve(grid, TestGrids.randomFreePoint(random, costmap),
                        List.of(TestGrids.randomFreePoint(random, costmap)));
                function.compute(request.goalCells(), -1);
                if (!function.isReached(request.startCell())) {
                    continue;
                }
                double[] decided = GradientDescent.descend(grid, function.potential(), MODEL.densityTable(),
                        MODEL.minDensity(), request.startX(), request.startY(), request.goalPoints(), true);
                double[] walked = GradientDescent.descend(grid, function.potential(), MODEL.densityTable(),
                        MODEL.minDensity(), request.startX(), request.startY(), request.goalPoints(), false);
                assertArrayEquals(walked, decided, "seed " + seed + ", goal " + goal);
                compared++;
            }
        }
        assertTrue(compared >= 50, compared + " paths compared");
    }

    @Test
    void freeRunsFollowTheGridsChanges() {
        Costmap costmap = TestGrids.random(7, 150, 60, 0.1);
        PlanningGrid grid = new PlanningGrid();
        grid.sync(costmap);
        assertRunsRecounted(grid);
        // a free row, then a graded cell in it far from its ends, one next to its left edge, one freed again
        for (int column = 0; column < 150; column++) {
            costmap.set(column, 30, Costmap.FREE);
        }
        grid.sync(costmap);
        assertRunsRecounted(grid);
        costmap.set(120, 30, 40);
        grid.sync(costmap);
        assertRunsRecounted(grid);
        costmap.set(0, 30, Costmap.LETHAL);
        costmap.set(149, 59, Costmap.FREE);
        grid.sync(costmap);
        assertRunsRecounted(grid);
        costmap.set(120, 30, Costmap.FREE);
        grid.sync(costmap);
        assertRunsRecounted(grid);
        assertEquals(PlanningGrid.MAX_FREE_RUN, grid.freeRuns()[grid.index(1, 30)], "a long run is capped");
        // another geometry with the same padded size: the old rows' runs must not show through the new ring
        grid.sync(TestGrids.free(60, 150));
        assertRunsRecounted(grid);
    }

    /** Each padded cell's run recounted from the costs: free cells rightwards in its row, capped. */
    private static void assertRunsRecounted(PlanningGrid grid) {
        byte[] costs = grid.costs();
        int stride = grid.stride();
        for (int i = 0; i < costs.length; i++) {
            int run = 0;
            while (run < PlanningGrid.MAX_FREE_RUN && (i + run) / stride == i / stride
                    && costs[i + run] == Costmap.FREE) {
                run++;
            }
            assertEquals(run, grid.freeRuns()[i], "run at column " + grid.column(i) + ", row " + grid.row(i));
        }
    }

    /** Lethal rectangles on free ground, no graded cells: free boxes everywhere between them. */
    private static Costmap rectangles(long seed, int width, int height, double fill) {
        Random random = new Random(seed);
        Costmap costmap = TestGrids.free(width, height);
        int covered = 0;
        while (covered < fill * width * height) {
            int c0 = random.nextInt(width);
            int r0 = random.nextInt(height);
            int w = 1 + random.nextInt(width / 6);
            int h = 1 + random.nextInt(height / 6);
            for (int r = r0; r < Math.min(height, r0 + h); r++) {
                for (int c = c0; c < Math.min(width, c0 + w); c++) {
                    if (costmap.cost(c, r) != Costmap.LETHAL) {
                        costmap.set(c, r, Costmap.LETHAL);
                        covered++;
                    }
                }
            }
        }
        return costmap;
    }

    /** A coordinate offset in [0, 8): an integer (a cell border), a half (a centre) or anything between. */
    private static double pick(Random random) {
        return switch (random.nextInt(3)) {
            case 0 -> random.nextInt(8);
            case 1 -> random.nextInt(8) + 0.5;
            default -> 8 * random.nextDouble();
        };
    }
}
