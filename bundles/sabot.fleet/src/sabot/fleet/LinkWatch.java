package sabot.fleet;

import java.time.Duration;
import java.util.Locale;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.TimeUnit;
import java.util.function.Consumer;

import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smackx.ping.packet.Ping;

/**
 * Notices a silent link — packets dropped, nothing closed (no FIN, no RST): a Wi-Fi dead spot — which TCP alone
 * reports only after minutes. Whatever arrives from the server proves the link; when nothing has arrived for one
 * interval the watch pings the server (XEP-0199, answered by the server itself, or refused, which proves the link just
 * as well), and when nothing has arrived for two intervals the link is silent: {@code silent} is told once, with the
 * time, and the session takes it as a loss (it goes offline, so a moving robot brakes, and reconnects with back-off).
 * The watch looks four times per interval, so silence is noticed within 2¼ intervals. Costs one small IQ per interval
 * on a link that carries nothing else. Both ends use it: the robot's session (which brakes a moving robot on the
 * loss) and the workbench's connection (which greys its robots and reconnects).
 */
public final class LinkWatch implements AutoCloseable {

    /** The default interval, s: a silent link is noticed within 2¼ s, so that a moving robot brakes. */
    public static final double DEFAULT_INTERVAL_S = 1;

    private final XMPPTCPConnection connection;
    private final long intervalMillis;
    private final Consumer<String> silent;
    private final ScheduledExecutorService timer;
    /** Timer thread only, besides {@link #online()}: when the current session came online, epoch ms. */
    private volatile long onlineSince = Long.MAX_VALUE;
    private volatile boolean reported;
    private volatile long lastPing;

    /**
     * Starts watching; nothing counts before {@link #online()}.
     *
     * @param interval the silence after which the server is pinged; twice it, the link is silent
     * @param threads  makes the watch's one thread (a daemon, named and prioritised as its owner's threads are)
     * @param silent   told why, once per session, on the watch's thread
     */
    public LinkWatch(XMPPTCPConnection connection, Duration interval, ThreadFactory threads, Consumer<String> silent) {
        this.connection = connection;
        this.timer = Executors.newSingleThreadScheduledExecutor(threads);
        this.intervalMillis = Math.max(1, interval.toMillis());
        this.silent = silent;
        long period = Math.max(1, intervalMillis / 4);
        timer.scheduleAtFixedRate(this::check, period, period, TimeUnit.MILLISECONDS);
    }

    /** A new session is online (logged in): the silence counts from now. */
    public void online() {
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
            // a ping that cannot be sent (the connection closed meanwhile): the loss is reported by the connection
        }
    }

    @Override
    public void close() {
        timer.shutdownNow();
    }
}
