package sabot.planner.internal;

import java.util.Arrays;

/**
 * The order in which {@link LpnNavigationFunction} expands a large bucket: by memory band (a block of
 * {@code 2^shift} consecutive padded cells, a row or so), stable within a band, in one counting pass. All cells of a
 * bucket are final, so any order gives the same values; memory order rather than the order the cells were reached
 * (which interleaves parts of the front pushed from different buckets) lets consecutive expansions share cache lines.
 * Small buckets are cheaper left in arrival order.
 *
 * <p>Why a class of its own: the sort runs once per bucket, outside the propagation's per-cell loop, and has its own
 * scratch arrays sized for the grid.
 */
final class MemoryBandOrder {

    /** A grid is cut into about 2^10 memory bands: a row or so on grids of 1000 x 1000. */
    private static final int BANDS_LOG2 = 10;

    private final int shift;
    /** Counts per band, one more than the number of bands plus one. */
    private final int[] counts;
    private int[] buffer = new int[0];

    /** @param paddedSize the number of padded cells of the grid */
    MemoryBandOrder(int paddedSize) {
        int bits = 32 - Integer.numberOfLeadingZeros(paddedSize);
        shift = Math.max(0, bits - BANDS_LOG2);
        counts = new int[(paddedSize >>> shift) + 2];
    }

    /** @return whether a bucket of {@code size} cells is worth ordering: an eighth of the bands or more */
    boolean isWorthSorting(int size) {
        return size >= counts.length >> 3;
    }

    /**
     * Orders the cells {@code items[from, from + size)} in place.
     *
     * @param capacity the room of a bucket, allocated for the scratch buffer when it is too small
     */
    void sort(int[] items, int from, int size, int capacity) {
        if (buffer.length < size) {
            buffer = new int[Math.max(size, capacity)];
        }
        sort(items, from, size, buffer, counts, shift);
        System.arraycopy(buffer, 0, items, from, size);
    }

    /**
     * Counting sort of the {@code size} cells {@code items[from, from + size)} by memory band ({@code cell >>> shift}),
     * stable within a band.
     *
     * @param buffer receives the sorted cells (at least {@code size} long)
     * @param counts scratch, one more than the number of bands plus one
     * @return {@code buffer}
     */
    static int[] sort(int[] items, int from, int size, int[] buffer, int[] counts, int shift) {
        // only the bands the front spans are cleared and summed: a bucket often covers a fraction of the grid
        int low = Integer.MAX_VALUE;
        int high = 0;
        for (int i = from; i < from + size; i++) {
            int band = items[i] >>> shift;
            low = Math.min(low, band);
            high = Math.max(high, band);
        }
        Arrays.fill(counts, low, high + 2, 0);
        for (int i = from; i < from + size; i++) {
            counts[(items[i] >>> shift) + 1]++;
        }
        for (int band = low + 1; band <= high + 1; band++) {
            counts[band] += counts[band - 1];
        }
        for (int i = from; i < from + size; i++) {
            int item = items[i];
            buffer[counts[item >>> shift]++] = item;
        }
        return buffer;
    }
}
