package sabot.workbench.fleet;

import java.time.Duration;
import java.time.Instant;
import java.util.Objects;

/**
 * How late a robot's poses reach the workbench, without comparing the two clocks (ControlML does not assume them
 * synchronised: docs/CONTROLML.md). A pose's <em>delay</em> is its receipt on the workbench's monotonic clock minus
 * its stamp on the robot's clock: the transit plus an unknown but constant offset. Its <em>lag</em> is its delay minus
 * the least delay seen from that robot, which cancels the offset: how much later than the robot's fastest pose it
 * came. A backlog anywhere on the way (the robot's writer, the server's fan-out, the workbench's ingest falling
 * behind on a busy CPU) shows as lag while the poses keep arriving.
 * <p>
 * Clocks that run at different rates: the least delay may rise by {@link #DRIFT_ALLOWANCE} of the time elapsed (1 ms a
 * second, ten times what quartz clocks drift), so drift never reads as lag; a lag that stays constant is absorbed at
 * that rate too (a 3 s lag falls below 2 s after 1,000 s). A robot clock stepped back (its stamps go backwards) starts
 * the measurement again; one stepped forward only lowers the delays. The workbench's own clock may step freely: the
 * receipt is read on the monotonic clock ({@link System#nanoTime()}).
 *
 * @param leastNanos    the least delay seen, raised by the drift allowance up to {@code receivedNanos}
 * @param lagNanos      the last pose's lag, ns; never negative
 * @param receivedNanos the last pose's receipt on the workbench's monotonic clock, ns
 * @param stamp         the last pose's stamp on the robot's clock; never null
 */
public record PoseLag(long leastNanos, long lagNanos, long receivedNanos, Instant stamp) {

    /** How fast the least delay may rise: the clocks' greatest rate difference accepted as drift (1 ms/s). */
    public static final double DRIFT_ALLOWANCE = 1e-3;

    public PoseLag {
        Objects.requireNonNull(stamp, "stamp");
        if (lagNanos < 0) {
            throw new IllegalArgumentException("lag < 0: " + lagNanos);
        }
    }

    /**
     * @param stamp         the first pose's stamp (robot clock)
     * @param receivedNanos its receipt on the workbench's monotonic clock, ns
     * @return the lag after a robot's first pose: zero, as nothing is known to be faster yet
     */
    public static PoseLag first(Instant stamp, long receivedNanos) {
        return new PoseLag(delay(stamp, receivedNanos), 0, receivedNanos, stamp);
    }

    /**
     * @param stamp         the next pose's stamp (robot clock)
     * @param receivedNanos its receipt on the workbench's monotonic clock, ns
     * @return the lag after that pose
     */
    public PoseLag next(Instant stamp, long receivedNanos) {
        if (stamp.isBefore(this.stamp)) {
            return first(stamp, receivedNanos); // the robot's clock stepped back: a new offset
        }
        long delay = delay(stamp, receivedNanos);
        long elapsed = Math.max(0, receivedNanos - this.receivedNanos);
        long least = Math.min(delay, leastNanos + (long) (elapsed * DRIFT_ALLOWANCE));
        return new PoseLag(least, delay - least, receivedNanos, stamp);
    }

    /** @return the last pose's lag: how much later than the robot's fastest pose it arrived */
    public Duration lag() {
        return Duration.ofNanos(lagNanos);
    }

    private static long delay(Instant stamp, long receivedNanos) {
        return receivedNanos - (stamp.getEpochSecond() * 1_000_000_000L + stamp.getNano());
    }
}
