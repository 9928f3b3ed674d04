package sabot.controlml.internal;

import java.util.ArrayList;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.OptionalLong;

import sabot.controlml.payload.TelemetryRates;
import sabot.controlml.payload.TelemetryRates.StreamRate;

/**
 * The leases of a device's telemetry (section 6 of {@code docs/CONTROLML.md}, "Leases"), without XMPP: which
 * resources it publishes (each at a base rate, and at most at a full rate), which watcher holds which rates until
 * when, and so the rate each resource is published at. Times are {@link System#nanoTime()}-like nanoseconds passed
 * in by the caller. Not thread-safe: the caller serialises.
 */
public final class LeaseBook {

    /** A resource the device publishes: always at {@code base} Hz, at most at {@code full} Hz while leased. */
    public record Offer(double base, double full) {
        public Offer {
            if (!(base >= 0 && full >= base)) {
                throw new IllegalArgumentException("need 0 <= base <= full, were " + base + ", " + full);
            }
        }
    }

    private record Lease(Map<String, Double> rates, long until) {
    }

    /** A resource asked for that the device does not publish: granted 0 Hz. */
    private static final Offer NOT_PUBLISHED = new Offer(0, 0);

    private final Map<String, Offer> offers = new LinkedHashMap<>();
    private final Map<String, Lease> leases = new HashMap<>();
    private final long maxLeaseNanos;

    /** @param maxLeaseSeconds the longest lease granted (a longer one is cut to it), &gt; 0 */
    public LeaseBook(double maxLeaseSeconds) {
        if (!(maxLeaseSeconds > 0 && maxLeaseSeconds <= TelemetryRates.MAX_LEASE_S)) {
            throw new IllegalArgumentException("longest lease must be in (0, " + TelemetryRates.MAX_LEASE_S
                    + "] s, was " + maxLeaseSeconds);
        }
        this.maxLeaseNanos = Math.round(maxLeaseSeconds * 1e9);
    }

    /** @return the longest lease granted, in seconds */
    public double maxLeaseSeconds() {
        return maxLeaseNanos / 1e9;
    }

    /** Adds (or replaces) a resource the device publishes. */
    public void offer(String resource, Offer offer) {
        offers.put(resource, offer);
    }

    /** @return the names of the resources published, in the order they were offered */
    public List<String> offered() {
        return List.copyOf(offers.keySet());
    }

    /**
     * Replaces a watcher's lease. A rate above a resource's full rate is granted as the full rate; a lease longer
     * than the device's longest is cut to it; a lease of 0 s, or one without a rate above 0, ends the watcher's lease.
     *
     * @return what the watcher gets: the lease granted, and for each resource asked the least rate it is published at
     *         while the lease lasts (0 for a resource the device does not publish)
     */
    public TelemetryRates grant(String watcher, TelemetryRates asked, long now) {
        long length = Math.min(maxLeaseNanos, Math.round(asked.lease() * 1e9));
        Map<String, Double> rates = new LinkedHashMap<>();
        List<StreamRate> granted = new ArrayList<>();
        for (StreamRate s : asked.streams()) {
            Offer o = offers.getOrDefault(s.resource(), NOT_PUBLISHED);
            double rate = length > 0 ? Math.min(s.rate(), o.full()) : 0;
            if (rate > 0) {
                rates.put(s.resource(), rate);
            }
            granted.add(new StreamRate(s.resource(), Math.max(o.base(), rate)));
        }
        if (rates.isEmpty()) {
            leases.remove(watcher);
            return new TelemetryRates(0, granted);
        }
        leases.put(watcher, new Lease(rates, now + length));
        return new TelemetryRates(length / 1e9, granted);
    }

    /** Ends a watcher's lease (it went offline). @return whether it held one */
    public boolean release(String watcher) {
        return leases.remove(watcher) != null;
    }

    /** Ends the leases whose time is up. @return whether any ended */
    public boolean expire(long now) {
        return leases.values().removeIf(l -> l.until() - now <= 0);
    }

    /** @return when the next lease ends, if one is held */
    public OptionalLong nextExpiry() {
        OptionalLong next = OptionalLong.empty();
        for (Lease l : leases.values()) {
            if (next.isEmpty() || l.until() - next.getAsLong() < 0) {
                next = OptionalLong.of(l.until());
            }
        }
        return next;
    }

    /** @return the rate a resource is published at: its base, raised by the leases held (not above its full rate) */
    public double rate(String resource) {
        Offer o = offers.get(resource);
        if (o == null) {
            return 0;
        }
        double rate = o.base();
        for (Lease l : leases.values()) {
            rate = Math.max(rate, l.rates().getOrDefault(resource, 0.0));
        }
        return Math.min(rate, o.full());
    }

    /** @return the number of watchers holding a lease */
    public int watchers() {
        return leases.size();
    }
}
