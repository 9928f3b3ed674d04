package sabot.controlml;

import java.time.Clock;
import java.time.LocalDate;
import java.time.ZoneOffset;

/**
 * Issues {@link RequestId}s for one requester. Thread-safe.
 * <p>
 * The counter of a day starts at the millisecond of the day times 32 (at most 2,764,800,000 &lt; 2^32) and then
 * counts up, so a requester that restarts the same day (same full JID) does not reuse the ids of its earlier run
 * unless it averaged more than 32 requests per millisecond. On a new UTC day the counter starts again.
 */
public final class RequestIdGenerator {

    private static final long SLOTS_PER_MILLISECOND = 32;

    private final Clock clock;
    private LocalDate day;
    private long next;

    /** @param clock the requester's clock (UTC day and time of day are taken from it) */
    public RequestIdGenerator(Clock clock) {
        this.clock = clock;
    }

    /** A generator on the system UTC clock. */
    public RequestIdGenerator() {
        this(Clock.systemUTC());
    }

    /** @return a fresh id */
    public synchronized RequestId next() {
        long now = clock.millis();
        LocalDate today = LocalDate.ofEpochDay(Math.floorDiv(now, 86_400_000L));
        if (!today.equals(day)) {
            day = today;
            next = Math.floorMod(now, 86_400_000L) * SLOTS_PER_MILLISECOND;
        }
        if (next > RequestId.MAX_COUNTER) {
            throw new IllegalStateException("request ids of " + day + " exhausted");
        }
        return new RequestId(day, next++);
    }

    /** @return the UTC zone ids are dated in */
    public static ZoneOffset zone() {
        return ZoneOffset.UTC;
    }
}
