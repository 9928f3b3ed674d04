package sabot.controlml.bench;

import java.lang.management.ManagementFactory;
import java.time.Instant;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.LongAdder;

import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.roster.AbstractPresenceEventListener;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.SubscribeListener.SubscribeAnswer;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.FullJid;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.TelemetryManager;
import sabot.controlml.TelemetryPublication;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * Robots publishing {@code cm.position} to PEP at a rate into subscribed workbenches, for a measurement window after a
 * warm-up (every subscriber has had an item from every robot): what {@code ./sabot bench controlml} (its telemetry
 * part) and {@code ./sabot bench fleet} measure. The robots log in to one node of the server, the subscribers to
 * another (the same on one server); latency is arrival minus the pose's time stamp (one JVM, one clock).
 */
final class TelemetryRun {

    /**
     * @param robots         publishing robots ({@code bench-robotN})
     * @param subscribers    subscribed workbenches ({@code bench-subN}), each mutually subscribed to every robot
     * @param rateHz         each robot's publication rate
     * @param durationS      the measurement window
     * @param textForm       payloads in ControlML's text form (else the XML form)
     * @param robotNode      the node the robots log in to (1 on one server)
     * @param subscriberNode the node the subscribers log in to
     * @param follow         subscribe explicitly to each robot's node (XEP-0060), for servers whose {@code +notify}
     *                       does not cross cluster nodes (ejabberd's per-node caps cache)
     */
    record Options(int robots, int subscribers, double rateHz, int durationS, boolean textForm, int robotNode,
            int subscriberNode, boolean follow) {
    }

    /**
     * @param sent          values published in the window (every attempt)
     * @param expected      {@code sent × subscribers}
     * @param delivered     window values received by the subscribers
     * @param sentTotal     every value published in the run (warm-up and settling included): accepted or failed
     * @param failed        publications that failed (in the run)
     * @param latenciesNs   the window's deliveries' latencies, sorted
     * @param wallS         the window's length as measured
     * @param setupS        from the first registration to the end of the warm-up
     * @param cpuPct        CPU over the window of each measured process tree, % of one core
     * @param rssMb         resident memory of each measured process tree at the window's end, MB
     * @param clientCpuPct  this JVM's CPU over the window (all clients), % of one core
     */
    record Result(long sent, long expected, long delivered, long sentTotal, long failed, long[] latenciesNs,
            double wallS, double setupS, Map<String, Double> cpuPct, Map<String, Double> rssMb,
            double clientCpuPct) {
    }

    private TelemetryRun() {
    }

    /**
     * @param measured the process trees whose CPU and memory are measured over the window, by name (a server node,
     *                 the database)
     */
    static Result run(PrivateXmppServer server, Options o, Map<String, Long> measured) throws Exception {
        System.out.printf("[bench] telemetry: %d robots x %.0f Hz -> %d subscribers for %d s%s%n", o.robots(), o
                .rateHz(), o.subscribers(), o.durationS(), o.robotNode() == o.subscriberNode() ? "" : " (robots on node "
                        + o.robotNode() + ", subscribers on node " + o.subscriberNode() + ")");
        long setup0 = System.nanoTime();
        List<XMPPTCPConnection> subs = new ArrayList<>();
        LongAdder delivered = new LongAdder();
        long[][] latencies = new long[o.subscribers()][];
        AtomicLong[] counts = new AtomicLong[o.subscribers()];
        CountDownLatch warm = new CountDownLatch(o.robots() * o.subscribers());
        long capacity = (long) (o.robots() * o.rateHz() * (o.durationS() + 30)) + 1000;
        Window window = new Window();
        for (int s = 0; s < o.subscribers(); s++) {
            String name = "bench-sub" + s;
            server.register(name, PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD);
            XMPPTCPConnection c = new XMPPTCPConnection(server.configuration(o.subscriberNode(), name,
                    PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD).setResource("wb").build());
            latencies[s] = new long[(int) Math.min(Integer.MAX_VALUE - 8, capacity)];
            counts[s] = new AtomicLong();
            int sub = s;
            Map<EntityBareJid, Boolean> seen = new ConcurrentHashMap<>();
            TelemetryManager.getInstanceFor(c).addListener(Resources.POSITION, (device, p) -> {
                long now = nanosOfInstant(Instant.now());
                if (seen.putIfAbsent(device, Boolean.TRUE) == null) {
                    warm.countDown();
                }
                long stamp = nanosOfInstant(p.time());
                if (window.contains(stamp)) {
                    long k = counts[sub].getAndIncrement();
                    if (k < latencies[sub].length) {
                        latencies[sub][(int) k] = now - stamp;
                    }
                    delivered.increment();
                }
            });
            c.connect().login();
            Roster.getInstanceFor(c).setSubscriptionMode(Roster.SubscriptionMode.accept_all);
            subs.add(c);
        }
        List<XMPPTCPConnection> robots = new ArrayList<>();
        CountDownLatch mutual = new CountDownLatch(o.robots() * o.subscribers() * 2);
        for (XMPPTCPConnection s : subs) {
            Roster.getInstanceFor(s).addPresenceEventListener(countAvailable(mutual, "bench-robot"));
        }
        Map<EntityBareJid, String> accounts = new LinkedHashMap<>();
        for (int r = 0; r < o.robots(); r++) {
            accounts.put(JidCreate.entityBareFrom("bench-robot" + r + "@" + PrivateXmppServer.DOMAIN),
                    PrivateXmppServer.DEFAULT_PASSWORD);
        }
        server.registerAll(accounts); // one call for the fleet: in-band registration is closed
        for (int r = 0; r < o.robots(); r++) {
            String name = "bench-robot" + r;
            XMPPTCPConnection c = new XMPPTCPConnection(server.configuration(o.robotNode(), name,
                    PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD).setResource("onboard").build());
            Roster roster = Roster.getInstanceFor(c);
            roster.addSubscribeListener((from, request) -> SubscribeAnswer.ApproveAndAlsoRequestIfRequired);
            roster.addPresenceEventListener(countAvailable(mutual, "bench-sub"));
            c.connect().login();
            robots.add(c);
            for (XMPPTCPConnection s : subs) {
                Roster.getInstanceFor(s).createItemAndRequestSubscription(c.getUser().asEntityBareJid(), name, null);
            }
        }
        if (!mutual.await(SETUP_WAIT_S, TimeUnit.SECONDS)) {
            // a server that lost a subscription under the setup's load: measured as it is, its pairs' items lost
            System.out.printf("[bench] warning: %d of %d presence subscriptions not complete after %d s; their "
                    + "telemetry counts as lost%n", mutual.getCount(), o.robots() * o.subscribers() * 2, SETUP_WAIT_S);
        }
        // Publish until every subscriber has had an item from every robot: the robots' servers learn the
        // subscribers' +notify from their entity caps asynchronously.
        LongAdder offered = new LongAdder();
        List<TelemetryPublication> publications = new ArrayList<>();
        for (XMPPTCPConnection c : robots) {
            AtomicLong seq = new AtomicLong();
            ControlMlManager.getInstanceFor(c).setTextForm(o.textForm());
            publications.add(TelemetryManager.getInstanceFor(c).publish(Resources.POSITION, () -> {
                Instant now = Instant.now();
                if (window.contains(nanosOfInstant(now))) {
                    offered.increment();
                }
                return new PoseEstimate(now, new Pose2D(seq.incrementAndGet(), 0, 0), PoseCovariance.ZERO);
            }, o.rateHz()));
        }
        if (o.follow()) {
            follow(subs, robots);
        }
        if (!warm.await(SETUP_WAIT_S, TimeUnit.SECONDS)) {
            System.out.printf("[bench] warning: warm-up incomplete after %d s: %d robot/subscriber pairs silent; "
                    + "measured as they are%n", SETUP_WAIT_S, warm.getCount());
        }
        double setupS = (System.nanoTime() - setup0) / 1e9;
        System.out.printf("[bench] setup (accounts, logins, %d mutual subscriptions, warm-up) %.1f s%n", o.robots()
                * o.subscribers(), setupS);
        Map<String, Long> cpu0 = new LinkedHashMap<>();
        measured.forEach((name, pid) -> cpu0.put(name, ProcStat.cpuTicks(pid)));
        long self0 = processCpuNanos();
        long wall0 = System.nanoTime();
        // The window opens a little after it is set: a value stamped at its start is then counted by its publisher
        // (offered) and by its subscribers (delivered) alike; opened at once, a publisher that read the time just
        // before the window's fields were written would not count a value its subscribers count (lost -2 was seen).
        long lead = TimeUnit.MILLISECONDS.toNanos(WINDOW_LEAD_MS);
        window.open(nanosOfInstant(Instant.now()) + lead, TimeUnit.SECONDS.toNanos(o.durationS()));
        // The measurement is the passing of time itself: wait out the window (latch never counted down).
        new CountDownLatch(1).await(TimeUnit.SECONDS.toNanos(o.durationS()) + lead, TimeUnit.NANOSECONDS);
        double wallS = (System.nanoTime() - wall0) / 1e9;
        Map<String, Double> cpuPct = new LinkedHashMap<>();
        Map<String, Double> rssMb = new LinkedHashMap<>();
        measured.forEach((name, pid) -> {
            cpuPct.put(name, 100.0 * (ProcStat.cpuTicks(pid) - cpu0.get(name)) / 100.0 / wallS); // ticks of 1/100 s
            rssMb.put(name, ProcStat.rssKb(pid) / 1024.0);
        });
        double clientCpuPct = 100.0 * (processCpuNanos() - self0) / 1e9 / wallS;
        publications.forEach(TelemetryPublication::stop);
        // let items still in flight arrive: wait until the delivered count stops growing for 2 s (at most 15 s)
        long last = -1;
        long settle = System.nanoTime() + TimeUnit.SECONDS.toNanos(15);
        while (delivered.sum() != last && System.nanoTime() < settle) {
            last = delivered.sum();
            new CountDownLatch(1).await(2, TimeUnit.SECONDS);
        }
        List<Long> all = new ArrayList<>();
        for (int s = 0; s < o.subscribers(); s++) {
            long n = Math.min(counts[s].get(), latencies[s].length);
            for (int i = 0; i < n; i++) {
                all.add(latencies[s][i]);
            }
        }
        long[] lat = all.stream().mapToLong(Long::longValue).sorted().toArray();
        long published = 0;
        long failed = 0;
        for (XMPPTCPConnection c : robots) {
            var stats = TelemetryManager.getInstanceFor(c).statistics();
            published += stats.published();
            failed += stats.failed();
        }
        for (XMPPTCPConnection c : robots) {
            c.instantShutdown();
        }
        for (XMPPTCPConnection c : subs) {
            c.instantShutdown();
        }
        return new Result(offered.sum(), offered.sum() * o.subscribers(), delivered.sum(), published + failed, failed,
                lat, wallS, setupS, cpuPct, rssMb, clientCpuPct);
    }

    /**
     * Each subscriber subscribes to each robot's position node (item-not-found until its first publication). A pair
     * still refused at the deadline (e.g. {@code not-authorized}: its presence subscription never completed) is
     * reported and measured as it is.
     */
    private static void follow(List<XMPPTCPConnection> subs, List<XMPPTCPConnection> robots) throws Exception {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(SETUP_WAIT_S);
        for (XMPPTCPConnection s : subs) {
            TelemetryManager telemetry = TelemetryManager.getInstanceFor(s);
            for (XMPPTCPConnection r : robots) {
                Outcome<Void> followed;
                do {
                    followed = telemetry.follow(r.getUser().asEntityBareJid(), Resources.POSITION);
                    if (!followed.isSuccess() && System.nanoTime() > deadline) {
                        System.out.printf("[bench] warning: %s cannot follow %s: %s; measured as it is%n", s
                                .getUser(), r.getUser(), followed.errorOrNull());
                        break;
                    }
                } while (!followed.isSuccess());
            }
        }
    }

    private static long processCpuNanos() {
        return ((com.sun.management.OperatingSystemMXBean) ManagementFactory.getOperatingSystemMXBean())
                .getProcessCpuTime();
    }

    /** Longest wait for the presence subscriptions, and for the warm-up, before measuring what there is. */
    private static final long SETUP_WAIT_S = 120;

    /** How long after it is set the measurement window opens. */
    private static final long WINDOW_LEAD_MS = 100;

    /** The measurement window in epoch nanoseconds; closed until opened. */
    private static final class Window {
        private volatile long start = Long.MAX_VALUE;
        private volatile long end = Long.MIN_VALUE;

        void open(long from, long length) {
            end = from + length;
            start = from;
        }

        boolean contains(long t) {
            return t >= start && t < end;
        }
    }

    private static AbstractPresenceEventListener countAvailable(CountDownLatch latch, String prefix) {
        Map<EntityBareJid, Boolean> seen = new ConcurrentHashMap<>();
        return new AbstractPresenceEventListener() {
            @Override
            public void presenceAvailable(FullJid address, Presence availablePresence) {
                EntityBareJid bare = address.asEntityBareJidIfPossible();
                if (bare != null && bare.getLocalpart().toString().startsWith(prefix) && seen.putIfAbsent(bare,
                        Boolean.TRUE) == null) {
                    latch.countDown();
                }
            }
        };
    }

    static long nanosOfInstant(Instant t) {
        return t.getEpochSecond() * 1_000_000_000L + t.getNano();
    }
}
