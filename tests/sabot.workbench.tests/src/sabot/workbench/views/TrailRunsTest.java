package sabot.workbench.views;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;

import org.junit.jupiter.api.Test;

/** The trail drawn: laps over the same pixels are stroked once. */
class TrailRunsTest {

    @Test
    void aTrailThatNeverReturnsIsOneRun() {
        int[] xy = { 0, 0, 10, 0, 20, 0, 30, 5 };
        List<int[]> runs = TrailRuns.runs(xy, 4);
        assertEquals(1, runs.size());
        assertArrayEquals(xy, runs.get(0));
    }

    @Test
    void aSecondLapOverTheSamePixelsIsLeftOutAndTheWayOnIsKept() {
        // a square lap, the same lap again, then away to the right
        int[] lap = { 0, 0, 20, 0, 20, 20, 0, 20 };
        int[] xy = new int[lap.length * 2 + 4];
        System.arraycopy(lap, 0, xy, 0, lap.length);
        System.arraycopy(lap, 0, xy, lap.length, lap.length);
        xy[2 * lap.length] = 40;
        xy[2 * lap.length + 1] = 20;
        xy[2 * lap.length + 2] = 60;
        xy[2 * lap.length + 3] = 20;
        List<int[]> runs = TrailRuns.runs(xy, 4);
        int segments = runs.stream().mapToInt(r -> r.length / 2 - 1).sum();
        // first lap: 3 segments + the closing one back to (0, 0); then (0, 20) -> (40, 20) -> (60, 20)
        assertEquals(6, segments, () -> runs.stream().map(java.util.Arrays::toString).toList().toString());
        int[] last = runs.get(runs.size() - 1);
        assertArrayEquals(new int[] { 0, 20, 40, 20, 60, 20 }, last);
        assertTrue(runs.get(0)[0] == 0 && runs.get(0)[1] == 0);
    }

    @Test
    void theCellSetHoldsEachCellOnceWhateverItsCoordinates() {
        TrailRuns.CellSet set = new TrailRuns.CellSet(5000);
        java.util.Set<Long> reference = new java.util.HashSet<>();
        java.util.Random random = new java.util.Random(17);
        int[] extremes = { Integer.MIN_VALUE, -1, 0, 1, Integer.MAX_VALUE };
        for (int i = 0; i < 5000; i++) {
            // small coordinates (many repeats) and the extremes (the table's free-slot key among them)
            int col = i % 7 == 0 ? extremes[random.nextInt(5)] : random.nextInt(60) - 30;
            int row = i % 11 == 0 ? extremes[random.nextInt(5)] : random.nextInt(60) - 30;
            boolean expected = reference.add((long) col << 32 | (row & 0xffffffffL));
            assertEquals(expected, set.add(col, row), "cell " + col + "," + row + " at " + i);
        }
    }
}
