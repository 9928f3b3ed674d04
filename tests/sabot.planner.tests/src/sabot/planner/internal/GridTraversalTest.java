package sabot.planner.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.Random;

import org.junit.jupiter.api.Test;

/**
 * The line integral of {@link GridTraversal}: the length inside each crossed cell times its density, a corner touched
 * in a point only counts nothing, an infinite density anywhere on the segment is infinite, and the bounded walk
 * stops above its limit. A segment inside one cell is answered without the walk: the same value.
 */
class GridTraversalTest {

    /** Density of cell (c, r) on a 4 x 4 grid: 1 + c + 4 r, infinite at (2, 2); infinite outside. */
    private static final GridTraversal.CellDensity DENSITY = (c, r) -> c < 0 || r < 0 || c > 3 || r > 3
            || c == 2 && r == 2 ? Double.POSITIVE_INFINITY : 1 + c + 4 * r;

    @Test
    void aSegmentInsideOneCellIsItsLengthTimesTheCellsDensity() {
        Random random = new Random(17);
        for (int i = 0; i < 1000; i++) {
            int c = random.nextInt(4);
            int r = random.nextInt(4);
            double x0 = c + random.nextDouble();
            double y0 = r + random.nextDouble();
            double x1 = c + random.nextDouble();
            double y1 = r + random.nextDouble();
            double length = Math.sqrt((x1 - x0) * (x1 - x0) + (y1 - y0) * (y1 - y0));
            double expected = c == 2 && r == 2 ? Double.POSITIVE_INFINITY : length * (1 + c + 4 * r);
            assertEquals(expected, GridTraversal.integrate(x0, y0, x1, y1, DENSITY), "segment " + i);
            assertEquals(expected, GridTraversal.integrate(x0, y0, x1, y1, DENSITY, 1e9), "bounded, segment " + i);
        }
        assertEquals(0, GridTraversal.integrate(2.5, 2.5, 2.5, 2.5, (c, r) -> 3));
        assertEquals(Double.POSITIVE_INFINITY, GridTraversal.integrate(2.5, 2.5, 2.5, 2.5, DENSITY),
                "a point in an impassable cell");
    }

    @Test
    void aSegmentAcrossCellsSumsItsPieces() {
        // along row 0: half of (0, 0), all of (1, 0), half of (2, 0)
        assertEquals(0.5 * 1 + 2 + 0.5 * 3, GridTraversal.integrate(0.5, 0.5, 2.5, 0.5, DENSITY), 1e-12);
        // down column 1: a quarter of (1, 0), all of (1, 1), three quarters of (1, 2)
        assertEquals(0.25 * 2 + 6 + 0.75 * 10, GridTraversal.integrate(1.75, 0.75, 1.75, 2.75, DENSITY), 1e-12);
        // the diagonal through the corner (1, 1): (0, 0) and (1, 1) only, (1, 0) and (0, 1) touched in a point
        assertEquals(Math.sqrt(0.5) * (1 + 6), GridTraversal.integrate(0.5, 0.5, 1.5, 1.5, DENSITY), 1e-12);
        // the same cells whichever way it is walked
        assertEquals(GridTraversal.integrate(0.5, 0.5, 2.5, 0.5, DENSITY),
                GridTraversal.integrate(2.5, 0.5, 0.5, 0.5, DENSITY), 1e-12);
    }

    @Test
    void anImpassableCellOnTheWayIsInfiniteAndTheBoundStopsTheWalk() {
        assertEquals(Double.POSITIVE_INFINITY, GridTraversal.integrate(0.5, 2.5, 3.5, 2.5, DENSITY));
        assertEquals(Double.POSITIVE_INFINITY, GridTraversal.integrate(1.0, 1.0, 3.0, 3.0, DENSITY));
        // through the impassable cell's corner point (2, 2) only: (1, 2) and (2, 1), finite
        assertEquals(Math.sqrt(0.5) * (10 + 7), GridTraversal.integrate(1.5, 2.5, 2.5, 1.5, DENSITY), 1e-12);
        // bounded: a partial sum above the limit, not the whole (0.5 + 2 + 1.5 = 4)
        double partial = GridTraversal.integrate(0.5, 0.5, 2.5, 0.5, DENSITY, 1.0);
        assertTrue(partial > 1.0 && partial < 4.0, "partial sum " + partial);
    }
}
