package sabot.workbench.views;

import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;

/**
 * A trail's screen polyline thinned for the renderer: points the eye cannot tell apart left out, and laps over cells
 * already passed cut out. Pure arithmetic on pixel coordinates, no SWT.
 */
final class TrailRuns {

    private TrailRuns() {
    }

    /**
     * A polyline's screen points ({@code x0, y0, x1, y1, ...}) without those closer than {@code minPx} (either axis) to
     * the last point kept; the last point is always kept: a trail holds up to 600 points, often laid over one another;
     * what the eye cannot tell apart the renderer need not stroke.
     */
    static int[] decimated(int[] xy, int minPx) {
        int[] out = new int[xy.length];
        int k = 0;
        int n = xy.length / 2;
        for (int i = 0; i < n; i++) {
            int x = xy[2 * i];
            int y = xy[2 * i + 1];
            boolean last = i == n - 1;
            if (k == 0 || last || Math.abs(x - out[k - 2]) >= minPx || Math.abs(y - out[k - 1]) >= minPx) {
                out[k++] = x;
                out[k++] = y;
            }
        }
        return Arrays.copyOf(out, k);
    }

    /**
     * A trail's screen polyline cut into runs that leave out segments between two points whose {@code cellPx} cells
     * the trail has already passed through: a robot that goes round the same loop (a patrol, a test circle) would
     * otherwise have its 600 points stroked lap over lap on the same pixels every frame.
     */
    static List<int[]> runs(int[] xy, int cellPx) {
        List<int[]> runs = new ArrayList<>();
        CellSet visited = new CellSet(xy.length / 2);
        int start = -1;
        boolean previousSeen = false;
        for (int i = 0; i < xy.length / 2; i++) {
            boolean seen = !visited.add(Math.floorDiv(xy[2 * i], cellPx), Math.floorDiv(xy[2 * i + 1], cellPx));
            if (seen && previousSeen) {
                if (start >= 0 && i - 1 > start) {
                    runs.add(Arrays.copyOfRange(xy, 2 * start, 2 * i));
                }
                start = i; // the segment to the next new point is drawn from here
            } else if (start < 0) {
                start = i;
            }
            previousSeen = seen;
        }
        if (start >= 0 && xy.length / 2 - 1 > start) {
            runs.add(Arrays.copyOfRange(xy, 2 * start, xy.length));
        }
        return runs;
    }

    /**
     * The cells a trail has passed through: an open-addressing hash set of cell coordinates in one {@code long[]}
     * (a {@code HashSet<Long>} boxed each of a trail's up to 600 points).
     */
    static final class CellSet {
        /** A free slot; the cell of that key, (Integer.MIN_VALUE, 0), is held by {@link #holdsEmptyKey}. */
        private static final long EMPTY = Long.MIN_VALUE;
        private final long[] keys;
        private final int mask;
        private boolean holdsEmptyKey;

        /** @param most the most cells it will hold (the table is at most half full) */
        CellSet(int most) {
            keys = new long[Integer.highestOneBit(Math.max(2, most) * 2 - 1) * 2];
            mask = keys.length - 1;
            Arrays.fill(keys, EMPTY);
        }

        /** @return true if cell (col, row) was not in the set (it is now) */
        boolean add(int col, int row) {
            long key = (long) col << 32 | (row & 0xffffffffL);
            if (key == EMPTY) {
                boolean added = !holdsEmptyKey;
                holdsEmptyKey = true;
                return added;
            }
            long h = key * 0x9E3779B97F4A7C15L;
            for (int i = (int) (h >>> 40) & mask;; i = (i + 1) & mask) {
                if (keys[i] == key) {
                    return false;
                }
                if (keys[i] == EMPTY) {
                    keys[i] = key;
                    return true;
                }
            }
        }
    }
}
