package sabot.onboard.portal.internal;

import java.time.Duration;
import java.util.ArrayDeque;
import java.util.Deque;
import java.util.HashMap;
import java.util.Iterator;
import java.util.Map;
import java.util.function.LongSupplier;

/**
 * Failed log-ins counted per client address and per account over a sliding window: once either has its
 * {@link Limits#failures()} within {@link Limits#window()}, further attempts are refused without asking the XMPP
 * server, until the oldest failure leaves the window. Bounded: at most {@value #MAX_KEYS} keys are remembered (the
 * stalest dropped first), so that a flood of invented accounts cannot grow it.
 */
final class LoginThrottle {

    /**
     * @param failures failed log-ins allowed within the window
     * @param window   the window
     */
    record Limits(int failures, Duration window) {
    }

    static final int MAX_KEYS = 4096;

    private final Limits limits;
    private final LongSupplier nanos;
    private final Map<String, Deque<Long>> failures = new HashMap<>();

    /** @param nanos a monotonic clock in nanoseconds ({@code System::nanoTime} in the product) */
    LoginThrottle(Limits limits, LongSupplier nanos) {
        this.limits = limits;
        this.nanos = nanos;
    }

    /**
     * @return zero when a log-in from {@code client} as {@code account} may be tried now; else how long until it may
     */
    synchronized Duration wait(String client, String account) {
        long now = nanos.getAsLong();
        return max(waitFor("client " + client, now), waitFor("account " + account, now));
    }

    /** Counts a failed log-in against the client and the account. */
    synchronized void failed(String client, String account) {
        long now = nanos.getAsLong();
        add("client " + client, now);
        add("account " + account, now);
    }

    private Duration waitFor(String key, long now) {
        Deque<Long> times = failures.get(key);
        if (times == null) {
            return Duration.ZERO;
        }
        prune(times, now);
        if (times.size() < limits.failures()) {
            return Duration.ZERO;
        }
        return Duration.ofNanos(times.peekFirst() + limits.window().toNanos() - now);
    }

    private void add(String key, long now) {
        if (!failures.containsKey(key) && failures.size() >= MAX_KEYS) {
            dropStalest(now);
        }
        Deque<Long> times = failures.computeIfAbsent(key, k -> new ArrayDeque<>());
        prune(times, now);
        times.addLast(now);
        while (times.size() > limits.failures()) {
            times.removeFirst();
        }
    }

    private void prune(Deque<Long> times, long now) {
        long window = limits.window().toNanos();
        while (!times.isEmpty() && now - times.peekFirst() >= window) {
            times.removeFirst();
        }
    }

    private void dropStalest(long now) {
        String stalest = null;
        long oldest = Long.MAX_VALUE;
        for (Iterator<Map.Entry<String, Deque<Long>>> it = failures.entrySet().iterator(); it.hasNext();) {
            Map.Entry<String, Deque<Long>> e = it.next();
            prune(e.getValue(), now);
            if (e.getValue().isEmpty()) {
                it.remove();
            } else if (e.getValue().peekLast() - now < oldest - now) {
                oldest = e.getValue().peekLast();
                stalest = e.getKey();
            }
        }
        if (stalest != null && failures.size() >= MAX_KEYS) {
            failures.remove(stalest);
        }
    }

    private static Duration max(Duration a, Duration b) {
        return a.compareTo(b) >= 0 ? a : b;
    }
}
