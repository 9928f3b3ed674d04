package sabot.controlml;

import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.OptionalLong;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.ScheduledThreadPoolExecutor;
import java.util.concurrent.TimeUnit;
import java.util.function.Supplier;

import org.jivesoftware.smack.StanzaListener;
import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.filter.PresenceTypeFilter;
import org.jivesoftware.smack.packet.Stanza;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.internal.LeaseBook;
import sabot.controlml.payload.TelemetryRates;
import sabot.controlml.payload.TelemetryRates.StreamRate;

/**
 * A device's telemetry at the rate its watchers look at (section 6 of {@code docs/CONTROLML.md}, "Leases"): each
 * resource {@link #offer offered} is published at a base rate, and faster, up to its full rate, while a watcher holds
 * a lease on it (a resource it does not publish is granted 0 Hz). A watcher leases with a {@code cm.telemetry} set
 * (observers may), renews it before it ends, and
 * ends it with a lease of 0 s or by going offline; {@code cm.telemetry} get answers the rates now. Made by
 * {@link TelemetryManager#serveLeases}; {@link #close} stops the publications and the handlers.
 */
public final class TelemetryLeases implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(TelemetryLeases.class);

    private final ControlMlManager manager;
    private final TelemetryManager telemetry;
    private final XMPPConnection connection;
    private final LeaseBook book;
    private final Map<String, TelemetryPublication> publications = new LinkedHashMap<>();
    private final StanzaListener unavailable = this::onUnavailable;
    private final ScheduledExecutorService timer;
    private ScheduledFuture<?> expiry; // guarded by this
    private boolean closed; // guarded by this

    TelemetryLeases(ControlMlManager manager, TelemetryManager telemetry, XMPPConnection connection,
            double maxLeaseSeconds) {
        this.manager = manager;
        this.telemetry = telemetry;
        this.connection = connection;
        this.book = new LeaseBook(maxLeaseSeconds);
        ScheduledThreadPoolExecutor t = new ScheduledThreadPoolExecutor(1, r -> {
            Thread thread = new Thread(r, "controlml-leases-" + connection.getXMPPServiceDomain());
            thread.setDaemon(true);
            return thread;
        });
        t.setRemoveOnCancelPolicy(true);
        this.timer = t;
        manager.onGet(Resources.TELEMETRY, (request, none) -> Outcome.success(rates()));
        manager.onSet(Resources.TELEMETRY, this::lease);
        connection.addAsyncStanzaListener(unavailable, PresenceTypeFilter.UNAVAILABLE);
    }

    /**
     * Publishes a resource at {@code baseHz}, and faster while leased, up to {@code fullHz}.
     *
     * @param baseHz the rate nobody needs to ask for, 0 (none) to {@code fullHz}
     * @param fullHz the highest rate a lease gets, at most {@value TelemetryRates#MAX_RATE_HZ}
     * @return the running publication (its rate follows the leases)
     */
    public synchronized <T> TelemetryPublication offer(Resource<T, ?> resource, Supplier<? extends T> source,
            double baseHz, double fullHz) {
        if (closed) {
            throw new IllegalStateException("leases closed");
        }
        if (publications.containsKey(resource.name())) {
            throw new IllegalArgumentException(resource.name() + " is offered already");
        }
        if (!(fullHz <= TelemetryRates.MAX_RATE_HZ)) {
            throw new IllegalArgumentException(resource.name() + ": full rate must be at most "
                    + TelemetryRates.MAX_RATE_HZ + " Hz, was " + fullHz);
        }
        book.offer(resource.name(), new LeaseBook.Offer(baseHz, fullHz));
        TelemetryPublication p = telemetry.publish(resource, source, book.rate(resource.name()));
        publications.put(resource.name(), p);
        return p;
    }

    /** @return the rate each offered resource is published at now, with the longest lease granted */
    public synchronized TelemetryRates rates() {
        List<StreamRate> streams = new ArrayList<>();
        for (String r : book.offered()) {
            streams.add(new StreamRate(r, book.rate(r)));
        }
        return new TelemetryRates(book.maxLeaseSeconds(), streams);
    }

    /** @return the number of watchers holding a lease now */
    public synchronized int watchers() {
        return book.watchers();
    }

    private synchronized Outcome<TelemetryRates> lease(Request request, TelemetryRates asked) {
        if (closed) {
            return Outcome.failure(ControlMlCondition.DEVICE_FAULT, "telemetry is stopping");
        }
        TelemetryRates granted = book.grant(request.from().toString(), asked, System.nanoTime());
        applyRates();
        return Outcome.success(granted);
    }

    private void onUnavailable(Stanza presence) {
        synchronized (this) {
            if (!closed && book.release(presence.getFrom().toString())) {
                LOG.debug("telemetry lease of {} ended: it went offline", presence.getFrom());
                applyRates();
            }
        }
    }

    /** Sets every publication's rate from the book and schedules the next expiry. Caller holds the lock. */
    private void applyRates() {
        book.expire(System.nanoTime());
        publications.forEach((name, p) -> p.setRate(book.rate(name)));
        if (expiry != null) {
            expiry.cancel(false);
            expiry = null;
        }
        OptionalLong next = book.nextExpiry();
        if (next.isPresent()) {
            expiry = timer.schedule(this::expire, Math.max(0, next.getAsLong() - System.nanoTime()),
                    TimeUnit.NANOSECONDS);
        }
    }

    private synchronized void expire() {
        if (!closed) {
            applyRates();
        }
    }

    /** Ends every lease, stops the publications and the {@code cm.telemetry} handlers. */
    @Override
    public void close() {
        synchronized (this) {
            if (closed) {
                return;
            }
            closed = true;
            publications.values().forEach(TelemetryPublication::stop);
            publications.clear();
        }
        manager.removeHandlers(Resources.TELEMETRY);
        connection.removeAsyncStanzaListener(unavailable);
        timer.shutdownNow();
    }
}
