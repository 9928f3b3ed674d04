package sabot.controlml;

import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.ScheduledThreadPoolExecutor;
import java.util.concurrent.TimeUnit;

import org.jxmpp.jid.Jid;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.payload.TelemetryRates;
import sabot.controlml.payload.TelemetryRates.StreamRate;

/**
 * A watcher's side of telemetry leases (section 6 of {@code docs/CONTROLML.md}, "Leases"): the rates this client asks
 * of each device it {@link #watch watches}, sent as {@code cm.telemetry} sets and renewed at half of each granted
 * lease, so that the device keeps them while this client looks and falls back to its base rates when it stops
 * (or goes away without a word). Sets do not wait for their answers ({@link ControlMlManager#setAsync}): a workbench
 * watches a thousand robots with one thread. Made by {@link TelemetryManager#watcher}.
 */
public final class TelemetryWatcher implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(TelemetryWatcher.class);

    private final ControlMlManager manager;
    private final double leaseSeconds;
    private final ScheduledExecutorService timer;
    private final Map<Jid, Watch> watches = new HashMap<>(); // guarded by this
    private long generation; // guarded by this
    private boolean closed; // guarded by this

    /** What is asked of one device: the rates, which request is the latest, the next renewal. */
    private static final class Watch {
        TelemetryRates asked;
        long generation;
        ScheduledFuture<?> renewal;
    }

    TelemetryWatcher(ControlMlManager manager, double leaseSeconds, String name) {
        if (!(leaseSeconds > 0 && leaseSeconds <= TelemetryRates.MAX_LEASE_S)) {
            throw new IllegalArgumentException("lease must be in (0, " + TelemetryRates.MAX_LEASE_S + "] s, was "
                    + leaseSeconds);
        }
        this.manager = manager;
        this.leaseSeconds = leaseSeconds;
        ScheduledThreadPoolExecutor t = new ScheduledThreadPoolExecutor(1, r -> {
            Thread thread = new Thread(r, "controlml-watcher-" + name);
            thread.setDaemon(true);
            return thread;
        });
        t.setRemoveOnCancelPolicy(true);
        this.timer = t;
    }

    /**
     * Asks a device for these rates from now on (replacing what was asked of it), and keeps asking until
     * {@link #watch} with no rates, or {@link #close}. Sent at once when the rates differ from what was asked.
     *
     * @param device the device's full JID (a request goes to a resource)
     * @param rates  by resource, Hz &gt; 0; empty: stop watching (the device is told, lease 0)
     */
    public synchronized void watch(Jid device, Map<Resource<?, ?>, Double> rates) {
        if (closed) {
            return;
        }
        List<StreamRate> streams = new ArrayList<>();
        rates.forEach((r, hz) -> streams.add(new StreamRate(r.name(), hz)));
        Watch w = watches.get(device);
        if (streams.isEmpty()) {
            if (w != null) {
                cancel(w);
                watches.remove(device);
                send(device, new TelemetryRates(0, List.of()), null);
            }
            return;
        }
        TelemetryRates asked = new TelemetryRates(leaseSeconds, streams);
        if (w != null && w.asked.equals(asked)) {
            return;
        }
        if (w == null) {
            w = new Watch();
            watches.put(device, w);
        }
        w.asked = asked;
        renew(device);
    }

    /** Sends a device's lease again now (e.g. it has come back online and may have forgotten it). */
    public synchronized void renew(Jid device) {
        Watch w = watches.get(device);
        if (w == null || closed) {
            return;
        }
        cancel(w);
        w.generation = ++generation;
        send(device, w.asked, w);
    }

    private void send(Jid device, TelemetryRates asked, Watch w) {
        long sentGeneration = w == null ? 0 : w.generation;
        manager.setAsync(device, Resources.TELEMETRY, asked).thenAccept(o -> answered(device, w, sentGeneration, o));
    }

    private synchronized void answered(Jid device, Watch w, long sentGeneration, Outcome<TelemetryRates> o) {
        if (w == null || closed || watches.get(device) != w || w.generation != sentGeneration) {
            return; // an answer to an end of lease, or to a request since replaced
        }
        double next;
        if (o.isSuccess() && o.orElseThrow() != null) {
            TelemetryRates g = o.orElseThrow();
            next = g.lease() > 0 ? g.lease() / 2 : leaseSeconds / 2;
        } else {
            LOG.debug("telemetry lease of {} not granted: {}", device, o.errorOrNull());
            next = leaseSeconds / 2; // offline, or refused: ask again later (renew() when it is back)
        }
        w.renewal = timer.schedule(() -> renew(device), Math.round(next * 1e9), TimeUnit.NANOSECONDS);
    }

    private static void cancel(Watch w) {
        if (w.renewal != null) {
            w.renewal.cancel(false);
            w.renewal = null;
        }
    }

    /** Ends every lease (each device is told) and stops renewing. */
    @Override
    public void close() {
        List<Jid> devices;
        synchronized (this) {
            if (closed) {
                return;
            }
            devices = new ArrayList<>(watches.keySet());
            watches.values().forEach(TelemetryWatcher::cancel);
            watches.clear();
            closed = true;
        }
        for (Jid d : devices) {
            send(d, new TelemetryRates(0, List.of()), null);
        }
        timer.shutdownNow();
    }
}
