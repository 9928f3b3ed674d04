package sabot.onboard.motion.loop;

import java.time.Instant;

/** A clock that stands still until a test advances it. */
final class FakeClock implements LoopClock {

    private long nanos = 1_000_000_000L;

    void advance(long by) {
        nanos += by;
    }

    double seconds() {
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
