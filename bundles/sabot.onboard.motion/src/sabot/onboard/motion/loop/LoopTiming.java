package sabot.onboard.motion.loop;

import java.util.Locale;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Measures the control loop: the jitter of each period's start against its schedule (|actual − expected|), the time
 * the period's work took, and how many optional reads were skipped for lack of bus time. Histograms in microseconds
 * ({@link MicrosHistogram}). Written by the loop's thread; summaries may be read from any thread (slightly stale).
 */
public final class LoopTiming {

    private final long periodNanos;
    private final MicrosHistogram jitter = new MicrosHistogram();
    private final MicrosHistogram busy = new MicrosHistogram();
    private long expected = Long.MIN_VALUE;
    private long started;
    private long periods;
    private long overruns;
    private long skipped;
    private long lastLate;
    private long lastEnd;
    /** A start this late (ns) begins a late run worth a log line (diagnosis of the jitter's tail). */
    private static final long LATE_NANOS = 10_000_000;
    private static final Logger LOG = LoggerFactory.getLogger("sabot.motion");
    private volatile Summary summary = new Summary(0, 0, 0, 0, 0, 0, 0, 0);

    /** Percentiles in microseconds. */
    public record Summary(long periods, double jitterP50, double jitterP99, double jitterMax, double busyP50, double busyP99,
            long overruns, long skippedOptionalReads) {
        @Override
        public String toString() {
            return String.format(Locale.ROOT,
                    "%d periods, start jitter p50 %.0f us p99 %.0f us max %.0f us, work p50 %.1f ms p99 %.1f ms, "
                            + "%d overruns, %d optional reads skipped",
                    periods, jitterP50, jitterP99, jitterMax, busyP50 / 1000, busyP99 / 1000, overruns,
                    skippedOptionalReads);
        }
    }

    LoopTiming(long periodNanos) {
        this.periodNanos = periodNanos;
    }

    public long periodNanos() {
        return periodNanos;
    }

    /** @return when the next period is due (the loop clock's nanoTime); meaningful once a period has started */
    long nextStartNanos() {
        return expected;
    }

    /** @return when the last period's work ended (the loop clock's nanoTime); meaningful once a period has ended */
    long lastEndNanos() {
        return lastEnd;
    }

    /**
     * A period started.
     *
     * @param now       the loop clock's nanoTime at its start
     * @param scheduled when the executor had it due (the loop clock's nanoTime): its own schedule, read inside the
     *                  period, so that the measurement carries no offset of its own
     */
    void started(long now, long scheduled) {
        long late = Math.abs(now - scheduled);
        jitter.add(late);
        if (late > LATE_NANOS && lastLate <= LATE_NANOS) {
            LOG.info("control loop period started {} ms late (the previous period's work took {} ms)",
                    String.format(Locale.ROOT, "%.1f", late * 1e-6),
                    String.format(Locale.ROOT, "%.1f", (lastEnd - started) * 1e-6));
        }
        lastLate = late;
        // a fixed-rate schedule runs a missed period late rather than skipping it: each start is due one period after
        // the previous start was due
        expected = scheduled + periodNanos;
        started = now;
    }

    void ended(long now) {
        lastEnd = now;
        long work = now - started;
        busy.add(work);
        if (work > periodNanos) {
            overruns++;
        }
        if (++periods % 50 == 0) {
            summary = compute();
        }
    }

    void skippedOptionalRead() {
        skipped++;
    }

    public Summary summary() {
        return summary;
    }

    private Summary compute() {
        return new Summary(periods, jitter.percentile(0.50), jitter.percentile(0.99), jitter.max(),
                busy.percentile(0.50), busy.percentile(0.99), overruns, skipped);
    }
}
