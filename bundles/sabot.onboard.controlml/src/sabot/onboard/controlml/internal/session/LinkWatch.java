package sabot.onboard.controlml.internal.session;

import java.time.Duration;
import java.util.Locale;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;
import java.util.function.Consumer;

import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smackx.ping.packet.Ping;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.onboard.task.NamedThreads;

/**
 * Notices a silent link — packets dropped, nothing closed (no FIN, no RST): a Wi-Fi dead spot — which TCP alone
 * reports only after minutes. Whatever arrives from the server proves the link; when nothing has arrived for one
 * interval the watch pings the server (XEP-0199, answered by the server itself, or refused, which proves the link just
 * as well), and when nothing has arrived for two intervals the link is silent: {@code silent} is told once, with the
 * time, and the session takes it as a loss (it goes offline, so a moving robot brakes, and reconnects with back-off).
 * The watch looks four times per interval, so silence is noticed within 2¼ intervals. Costs one small IQ per interval
 * on a link that carries nothing else.
 */
final class LinkWatch implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(LinkWatch.class);

    private final XMPPTCPConnection connection;
    private final long intervalMillis;
    private final Consumer<String> silent;
    private final ScheduledExecutorService timer = Executors.newSingleThreadScheduledExecutor(NamedThreads.daemon(
            "sabot-session-liveness"));
    /** Timer thread only, besides {@link #online()}: when the current session came online, epoch ms. */
    private volatile long onlineSince = Long.MAX_VALUE;
    private volatile boolean reported;
    private volatile long lastPing;

    /**
     * @param interval the silence after which the server is pinged; twice it, the link is silent
     * @param silent   told why, once per session, on the watch's thread
     */
    LinkWatch(XMPPTCPConnection connection, Duration interval, Consumer<String> silent) {
        this.connection = connection;
        this.intervalMillis = Math.max(1, interval.toMillis());
        this.silent = silent;
        long period = Math.max(1, intervalMillis / 4);
        timer.scheduleAtFixedRate(this::check, period, period, TimeUnit.MILLISECONDS);
    }

    /** A new session is online: the silence counts from now. */
    void online() {
        lastPing = 0;
        reported = false;
        onlineSince = System.currentTimeMillis();
    }

    private void check() {
        try {
            long since = onlineSince;
            if (reported || since == Long.MAX_VALUE || !connection.isAuthenticated()) {
                return;
            }
            long now = System.currentTimeMillis();
            long heard = Math.max(since, connection.getLastStanzaReceived());
            long quiet = now - heard;
            if (quiet > 2 * intervalMillis) {
                reported = true;
                silent.accept(String.format(Locale.ROOT, "connection silent for %.1f s", quiet / 1000.0));
            } else if (quiet > intervalMillis && now - lastPing >= intervalMillis) {
                lastPing = now;
                // the answer (or an error) is a stanza received: it is what the next check looks at
                connection.sendIqRequestAsync(new Ping(connection, connection.getXMPPServiceDomain()),
                        2 * intervalMillis);
            }
        } catch (RuntimeException e) {
            LOG.debug("liveness check: {}", e.toString());
        }
    }

    @Override
    public void close() {
        timer.shutdownNow();
    }
}
