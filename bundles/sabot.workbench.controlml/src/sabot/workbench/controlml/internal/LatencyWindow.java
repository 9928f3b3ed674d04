package sabot.workbench.controlml.internal;

/**
 * Percentiles of durations over a sliding window, in bounded memory (plain Java: no OSGi, XMPP or SWT; the caller
 * gives the monotonic time).
 * <p>
 * Each duration goes into a logarithmic bucket: {@link #BUCKETS_PER_OCTAVE} buckets per doubling from
 * {@link #MIN_NANOS} (shorter durations share the first bucket) to {@link #MAX_NANOS} (longer ones share the last), so
 * that a percentile is the geometric middle of its bucket, within {@link #RELATIVE_ERROR} of the true value. The window
 * is {@code slices} slices of {@code sliceSeconds} each: a percentile covers the slices of the last
 * {@code slices × sliceSeconds} seconds, the current one included. Memory: {@code slices × BUCKETS} counters, whatever
 * the traffic.
 */
public final class LatencyWindow {

    /** The shortest duration told apart: 10 µs (a loopback round trip is 0.2 ms or more). */
    public static final long MIN_NANOS = 10_000L;
    /** The longest duration told apart: 2^24 × 10 µs ≈ 168 s (a request times out after 10 s by default). */
    public static final long MAX_NANOS = MIN_NANOS << 24;
    /** Buckets per doubling: each bucket is 2^(1/8) ≈ 1.09 times as wide as the one before. */
    public static final int BUCKETS_PER_OCTAVE = 8;
    /** The bucket count: 24 octaves. */
    public static final int BUCKETS = 24 * BUCKETS_PER_OCTAVE;
    /** The largest relative error of a percentile inside the range: half a bucket's width, 2^(1/16) - 1 ≈ 4.4 %. */
    public static final double RELATIVE_ERROR = Math.pow(2, 1.0 / (2 * BUCKETS_PER_OCTAVE)) - 1;

    private static final long SECOND = 1_000_000_000L;

    private final long sliceNanos;
    /** The slice index each row holds (a row of an older slice is stale: empty). */
    private final long[] sliceOf;
    private final int[][] counts;

    /**
     * @param slices       the window's slices, 1..60
     * @param sliceSeconds each slice's length in seconds, 1..3600
     */
    public LatencyWindow(int slices, int sliceSeconds) {
        if (slices < 1 || slices > 60 || sliceSeconds < 1 || sliceSeconds > 3600) {
            throw new IllegalArgumentException(slices + " slices of " + sliceSeconds
                    + " s: expected 1..60 slices of 1..3600 s");
        }
        sliceNanos = sliceSeconds * SECOND;
        sliceOf = new long[slices];
        java.util.Arrays.fill(sliceOf, Long.MIN_VALUE);
        counts = new int[slices][BUCKETS];
    }

    /** @return the window's length in seconds */
    public long seconds() {
        return sliceOf.length * sliceNanos / SECOND;
    }

    /**
     * Counts one duration.
     *
     * @param nanos    when it ended ({@code System.nanoTime()} scale)
     * @param duration its length in nanoseconds, 0 or more
     */
    public synchronized void add(long nanos, long duration) {
        long slice = Math.floorDiv(nanos, sliceNanos);
        int row = (int) Math.floorMod(slice, (long) sliceOf.length);
        if (sliceOf[row] != slice) {
            if (sliceOf[row] > slice) {
                return; // older than the window
            }
            sliceOf[row] = slice;
            java.util.Arrays.fill(counts[row], 0);
        }
        counts[row][bucketOf(duration)]++;
    }

    /** @return the durations counted in the window ending at {@code nowNanos} */
    public synchronized long count(long nowNanos) {
        long n = 0;
        long current = Math.floorDiv(nowNanos, sliceNanos);
        for (int row = 0; row < sliceOf.length; row++) {
            if (live(row, current)) {
                for (int c : counts[row]) {
                    n += c;
                }
            }
        }
        return n;
    }

    /**
     * @param q        the quantile, 0 < q ≤ 1 (0.5: the median; 0.99: p99)
     * @param nowNanos the window's end
     * @return the duration in nanoseconds that {@code q} of the window's durations do not exceed (nearest rank, the
     *         bucket's geometric middle); NaN when the window holds none
     */
    public synchronized double quantileNanos(double q, long nowNanos) {
        if (!(q > 0 && q <= 1)) {
            throw new IllegalArgumentException("quantile " + q + ": expected 0 < q <= 1");
        }
        long current = Math.floorDiv(nowNanos, sliceNanos);
        long[] merged = new long[BUCKETS];
        long n = 0;
        for (int row = 0; row < sliceOf.length; row++) {
            if (live(row, current)) {
                for (int b = 0; b < BUCKETS; b++) {
                    merged[b] += counts[row][b];
                    n += counts[row][b];
                }
            }
        }
        if (n == 0) {
            return Double.NaN;
        }
        long rank = (long) Math.ceil(q * n); // nearest rank: the rank-th smallest, 1-based
        long seen = 0;
        for (int b = 0; b < BUCKETS; b++) {
            seen += merged[b];
            if (seen >= rank) {
                return middleOf(b);
            }
        }
        return middleOf(BUCKETS - 1);
    }

    private boolean live(int row, long currentSlice) {
        return sliceOf[row] <= currentSlice && sliceOf[row] > currentSlice - sliceOf.length;
    }

    /** @return the bucket of a duration: floor(log2(d / MIN) × BUCKETS_PER_OCTAVE), clamped to the range */
    static int bucketOf(long duration) {
        if (duration <= MIN_NANOS) {
            return 0;
        }
        int b = (int) Math.floor(Math.log((double) duration / MIN_NANOS) / Math.log(2) * BUCKETS_PER_OCTAVE);
        return Math.min(b, BUCKETS - 1);
    }

    /** @return the geometric middle of bucket {@code b} in nanoseconds */
    static double middleOf(int b) {
        return MIN_NANOS * Math.pow(2, (b + 0.5) / BUCKETS_PER_OCTAVE);
    }
}
