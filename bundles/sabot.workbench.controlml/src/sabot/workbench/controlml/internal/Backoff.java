package sabot.workbench.controlml.internal;

import java.time.Duration;

/**
 * Reconnection back-off: the first wait is {@code min}, each further one doubles up to {@code max}; a successful
 * login resets it. Not thread-safe (the connection thread owns it).
 */
final class Backoff {

    private final Duration min;
    private final Duration max;
    private Duration next;

    Backoff(Duration min, Duration max) {
        if (min.isNegative() || min.isZero() || max.compareTo(min) < 0) {
            throw new IllegalArgumentException("back-off needs 0 < min <= max, was " + min + ", " + max);
        }
        this.min = min;
        this.max = max;
        this.next = min;
    }

    /** @return the wait before the next attempt; the one after will be twice as long (at most {@code max}) */
    Duration next() {
        Duration d = next;
        next = next.multipliedBy(2).compareTo(max) > 0 ? max : next.multipliedBy(2);
        return d;
    }

    /** Back to {@code min}. */
    void reset() {
        next = min;
    }
}
