package sabot.onboard.portal.internal;

import java.nio.charset.StandardCharsets;
import java.security.MessageDigest;
import java.security.SecureRandom;
import java.time.Duration;
import java.util.Base64;
import java.util.Iterator;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.Optional;
import java.util.function.LongSupplier;

/**
 * The page's log-ins: a random session id (256 bits, the cookie's value) to the account and its CSRF token (256
 * bits, a hidden field of every form that changes something). A session ends at log-out or after
 * {@code timeout} without a request; at most {@value #MAX_SESSIONS} live at once (a new log-in ends the least
 * recently used one).
 */
final class PortalSessions {

    static final int MAX_SESSIONS = 64;

    /**
     * @param id      the cookie's value
     * @param account the bare JID that logged in
     * @param csrf    the token its forms carry
     */
    record Session(String id, String account, String csrf) {

        /** @return true when {@code token} is this session's CSRF token (compared in constant time) */
        boolean csrfMatches(String token) {
            return token != null && MessageDigest.isEqual(csrf.getBytes(StandardCharsets.US_ASCII), token.getBytes(
                    StandardCharsets.US_ASCII));
        }
    }

    /** A session and the time of its last request (monotonic ns). */
    private static final class Live {
        final Session session;
        long lastRequest;

        Live(Session session, long lastRequest) {
            this.session = session;
            this.lastRequest = lastRequest;
        }
    }

    private final SecureRandom random = new SecureRandom();
    private final Duration timeout;
    private final LongSupplier nanos;
    /** Session id to session and its last request, in access order. Guarded by this. */
    private final LinkedHashMap<String, Live> sessions = new LinkedHashMap<>(16, 0.75f, true);

    PortalSessions(Duration timeout, LongSupplier nanos) {
        this.timeout = timeout;
        this.nanos = nanos;
    }

    /** @return a new session for {@code account} */
    synchronized Session open(String account) {
        expire();
        if (sessions.size() >= MAX_SESSIONS) {
            Iterator<String> eldest = sessions.keySet().iterator();
            eldest.next();
            eldest.remove();
        }
        Session s = new Session(token(), account, token());
        sessions.put(s.id(), new Live(s, nanos.getAsLong()));
        return s;
    }

    /** @return the live session of a cookie's value (its idle time restarted), or empty */
    synchronized Optional<Session> find(String id) {
        if (id == null) {
            return Optional.empty();
        }
        expire();
        Live live = sessions.get(id);
        if (live == null) {
            return Optional.empty();
        }
        live.lastRequest = nanos.getAsLong();
        return Optional.of(live.session);
    }

    synchronized void close(String id) {
        sessions.remove(id);
    }

    synchronized int size() {
        expire();
        return sessions.size();
    }

    private void expire() {
        long now = nanos.getAsLong();
        sessions.values().removeIf(l -> now - l.lastRequest >= timeout.toNanos());
    }

    private String token() {
        byte[] bytes = new byte[32];
        random.nextBytes(bytes);
        return Base64.getUrlEncoder().withoutPadding().encodeToString(bytes);
    }

    /** @return the sessions by id, for tests */
    synchronized Map<String, Session> snapshot() {
        Map<String, Session> copy = new LinkedHashMap<>();
        sessions.forEach((k, v) -> copy.put(k, v.session));
        return copy;
    }
}
