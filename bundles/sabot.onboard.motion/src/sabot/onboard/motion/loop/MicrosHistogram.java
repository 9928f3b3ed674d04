package sabot.onboard.motion.loop;

import java.util.Locale;

/**
 * Durations in 1 µs bins up to 100 ms (longer ones count in the last bin), so that percentiles over hours of control
 * periods cost no memory growth. Written by one thread; a reader on another thread may see a slightly stale state.
 */
public final class MicrosHistogram {

    private static final int BINS = 100_000;

    private final long[] bins = new long[BINS];
    private long count;

    void add(long nanos) {
        bins[(int) Math.max(0, Math.min(BINS - 1, nanos / 1000))]++;
        count++;
    }

    long count() {
        return count;
    }

    /** @return the {@code q} quantile in microseconds (0 when empty) */
    double percentile(double q) {
        long target = (long) Math.ceil(q * count);
        long seen = 0;
        for (int i = 0; i < BINS && count > 0; i++) {
            seen += bins[i];
            if (seen >= target && seen > 0) {
                return i;
            }
        }
        return 0;
    }

    /** @return the largest value's bin in microseconds (0 when empty) */
    double max() {
        for (int i = BINS - 1; i >= 0; i--) {
            if (bins[i] > 0) {
                return i;
            }
        }
        return 0;
    }

    /** @return e.g. {@code p50 1.2 ms p99 3.4 ms max 5.0 ms (n 1234)} */
    public String describe() {
        return String.format(Locale.ROOT, "p50 %.1f ms p99 %.1f ms max %.1f ms (n %d)", percentile(0.5) / 1000,
                percentile(0.99) / 1000, max() / 1000, count);
    }
}
