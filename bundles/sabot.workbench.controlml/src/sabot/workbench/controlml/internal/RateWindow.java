package sabot.workbench.controlml.internal;

/**
 * Events and their sizes per second over a sliding window of whole seconds (plain Java: no OSGi, XMPP or SWT; the
 * caller gives the monotonic time, so that a test drives it second by second).
 * <p>
 * One bucket per second of {@code System.nanoTime()}; a rate is the sum of the last {@link #seconds()} complete
 * seconds divided by their number (fewer right after the window's start, the first second counted from
 * {@code startNanos}): it lags by at most one second and is exact for a steady stream. Memory is two arrays of the
 * window's length, whatever the traffic.
 */
public final class RateWindow {

    private static final long SECOND = 1_000_000_000L;

    private final long startSecond;
    private final int seconds;
    /**
     * The second each bucket holds (a bucket of an older second is stale: empty): one more bucket than the window's
     * seconds, for the second under way.
     */
    private final long[] secondOf;
    private final long[] events;
    private final long[] amounts;
    private long totalEvents;
    private long totalAmount;

    /**
     * @param seconds    the window's length in whole seconds, 1..3600
     * @param startNanos when counting started ({@code System.nanoTime()} scale): seconds before it are not in a rate
     */
    public RateWindow(int seconds, long startNanos) {
        if (seconds < 1 || seconds > 3600) {
            throw new IllegalArgumentException("a rate window of " + seconds + " s: expected 1..3600 s");
        }
        this.startSecond = Math.floorDiv(startNanos, SECOND);
        this.seconds = seconds;
        secondOf = new long[seconds + 1];
        java.util.Arrays.fill(secondOf, Long.MIN_VALUE);
        events = new long[seconds + 1];
        amounts = new long[seconds + 1];
    }

    /** @return the window's length in seconds */
    public int seconds() {
        return seconds;
    }

    /**
     * Counts one event.
     *
     * @param nanos  when it happened ({@code System.nanoTime()} scale)
     * @param amount its size (bytes), 0 or more
     */
    public synchronized void add(long nanos, long amount) {
        long second = Math.floorDiv(nanos, SECOND);
        int i = (int) Math.floorMod(second, (long) secondOf.length);
        if (secondOf[i] != second) {
            if (secondOf[i] > second) {
                return; // older than the window (a caller's stale time): in the totals only
            }
            secondOf[i] = second;
            events[i] = 0;
            amounts[i] = 0;
        }
        events[i]++;
        amounts[i] += amount;
        totalEvents++;
        totalAmount += amount;
    }

    /** @return events per second over the complete seconds of the window before {@code nowNanos}; 0 before any */
    public synchronized double eventsPerSecond(long nowNanos) {
        return perSecond(nowNanos, events);
    }

    /** @return the amounts' sum per second, as {@link #eventsPerSecond} */
    public synchronized double amountPerSecond(long nowNanos) {
        return perSecond(nowNanos, amounts);
    }

    /** @return every event counted since the start */
    public synchronized long totalEvents() {
        return totalEvents;
    }

    /** @return the sum of every amount counted since the start */
    public synchronized long totalAmount() {
        return totalAmount;
    }

    private double perSecond(long nowNanos, long[] values) {
        long current = Math.floorDiv(nowNanos, SECOND);
        long complete = Math.min(seconds, current - startSecond);
        if (complete <= 0) {
            return 0;
        }
        long sum = 0;
        for (int k = 0; k < secondOf.length; k++) {
            if (secondOf[k] < current && secondOf[k] >= current - complete) {
                sum += values[k];
            }
        }
        return (double) sum / complete;
    }
}
