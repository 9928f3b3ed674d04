package sabot.onboard.motion.loop;

import java.time.Instant;

/**
 * A {@link LoopClock} that stands still until it is told to advance: the simulated time of the motion simulation and of
 * the loop's tests, which tick the loop period by period. Its wall clock is the same time after the epoch. Not
 * thread-safe: one thread ticks the loop and advances the clock.
 */
public final class ManualClock implements LoopClock {

    private long nanos;

    /** @param startNanos the time it shows first, ns */
    public ManualClock(long startNanos) {
        this.nanos = startNanos;
    }

    /** Moves the time on by {@code by} ns. */
    public void advance(long by) {
        if (by < 0) {
            throw new IllegalArgumentException("a clock does not go back: " + by + " ns");
        }
        nanos += by;
    }

    /** @return the time it shows, s */
    public double seconds() {
        return nanos * 1e-9;
    }

    @Override
    public long nanoTime() {
        return nanos;
    }

    @Override
    public Instant now() {
        return Instant.EPOCH.plusNanos(nanos);
    }
}
