package sabot.controlml.internal;

import java.time.Clock;
import java.time.Duration;
import java.time.Instant;
import java.util.Map;
import java.util.Objects;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.function.Consumer;

import org.jxmpp.jid.Jid;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The requesters' clocks as a device sees them, so that a set's send time ({@code sent}, on the requester's clock)
 * can be judged on the device's clock (docs/CONTROLML.md section 5). Each requester's offset is measured once per
 * presence, NTP-style, with one XEP-0202 entity-time query: {@code offset = remote − (t0 + t1) / 2}, uncertain by
 * half the round trip. A requester whose offset is not known (yet, or whose client does not answer XEP-0202) is taken
 * as synchronised (offset zero).
 * <p>
 * The queries run on a thread of their own ({@code measure}); {@link #offsetOf} never blocks.
 */
public final class ClockOffsets {

    private static final Logger LOG = LoggerFactory.getLogger(ClockOffsets.class);

    /**
     * One measurement.
     *
     * @param offset      the requester's clock minus the device's
     * @param uncertainty half the query's round trip
     */
    public record Offset(Duration offset, Duration uncertainty) {
    }

    /** The blocking query of a requester's clock: its time, or null when it does not tell. */
    @FunctionalInterface
    public interface RemoteClock {
        Instant timeOf(Jid requester) throws Exception;
    }

    private final Clock clock;
    private final RemoteClock remote;
    private final Consumer<Runnable> background;
    private final Map<Jid, Offset> offsets = new ConcurrentHashMap<>();
    private final Set<Jid> measuring = ConcurrentHashMap.newKeySet();

    /**
     * @param clock      the device's clock
     * @param remote     asks a requester for its time
     * @param background runs a measurement off the caller's thread
     */
    public ClockOffsets(Clock clock, RemoteClock remote, Consumer<Runnable> background) {
        this.clock = Objects.requireNonNull(clock);
        this.remote = Objects.requireNonNull(remote);
        this.background = Objects.requireNonNull(background);
    }

    /** @return the requester's measured offset, or null when none is known */
    public Offset of(Jid requester) {
        return offsets.get(requester);
    }

    /** @return the requester's clock minus the device's; zero when not measured */
    public Duration offsetOf(Jid requester) {
        Offset o = offsets.get(requester);
        return o == null ? Duration.ZERO : o.offset();
    }

    /** Measures the requester's offset in the background unless it is known or being measured. */
    public void measure(Jid requester) {
        if (offsets.containsKey(requester) || !measuring.add(requester)) {
            return;
        }
        background.accept(() -> {
            try {
                measureNow(requester);
            } finally {
                measuring.remove(requester);
            }
        });
    }

    /** Forgets a requester (it went offline: its next session may run on another clock). */
    public void forget(Jid requester) {
        offsets.remove(requester);
    }

    /** @return the measured offset, or null when the requester did not tell its time */
    Offset measureNow(Jid requester) {
        Instant t0 = clock.instant();
        Instant theirs;
        try {
            theirs = remote.timeOf(requester);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return null;
        } catch (Exception e) {
            LOG.info("clock of {} not measured ({}): its send times are taken as on this clock", requester, e
                    .toString());
            return null;
        }
        Instant t1 = clock.instant();
        if (theirs == null) {
            return null;
        }
        Duration half = Duration.between(t0, t1).dividedBy(2);
        Offset o = new Offset(Duration.between(t0.plus(half), theirs), half);
        offsets.put(requester, o);
        LOG.info("clock of {} differs from this one by {} ms (±{} ms)", requester, o.offset().toMillis(), half
                .toMillis());
        return o;
    }
}
