package sabot.controlml.bench;

import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.SmackConfiguration;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;

import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * {@code ./sabot bench fleet}: a fleet's telemetry through one server or the two-node ejabberd cluster, with or without
 * the archive (docs/CLUSTER.md, "Capacity"). Robots publish {@code cm.position} at a rate into subscribed workbenches
 * for a window; the last line printed is one JSON object: {@code robots}, {@code hz}, {@code server}, {@code sent}
 * (every publication of the window, failures included), {@code delivered}, {@code lost} ({@code sent × subscribers −
 * delivered}), {@code p50_ms}, {@code p99_ms}, with {@code --archive} {@code sent_total} (every value published in the
 * run) and {@code archived} (distinct values in PostgreSQL), and each server node's (and the database's) CPU over the
 * window and memory at its end. On the cluster the robots log in to node 1 and the subscribers to node 2.
 */
public final class FleetBench {

    private int robots = 1000;
    private double hz = 1;
    private String server = "ejabberd";
    private int subscribers = 2;
    private int seconds = 30;
    private boolean archive;

    private FleetBench() {
    }

    public static void main(String[] args) throws Exception {
        FleetBench b = new FleetBench();
        try {
            b.parse(args);
        } catch (IllegalArgumentException e) {
            System.err.println("[sabot] error: bench fleet: " + e.getMessage() + " (--help)");
            System.exit(2);
        }
        b.run();
        System.exit(0); // Smack's threads are not daemons
    }

    private void parse(String[] args) {
        for (int i = 0; i < args.length; i++) {
            String a = args[i];
            if (a.equals("--help") || a.equals("-h")) {
                System.out.println("usage: ./sabot bench fleet [--robots N (1000)] [--hz R (1)] "
                        + "[--server prosody|ejabberd|cluster (ejabberd)] [--subscribers S (2)] [--seconds T (30)] "
                        + "[--archive]");
                System.exit(0);
            }
            if (a.equals("--archive")) {
                archive = true;
                continue;
            }
            if (i + 1 >= args.length) {
                throw new IllegalArgumentException(a + " needs a value");
            }
            String v = args[++i];
            switch (a) {
                case "--robots" -> robots = whole(a, v, 1, 100_000);
                case "--hz" -> hz = rate(v);
                case "--server" -> {
                    if (!List.of("prosody", "ejabberd", "cluster").contains(v)) {
                        throw new IllegalArgumentException("--server '" + v + "': expected prosody, ejabberd or cluster");
                    }
                    server = v;
                }
                case "--subscribers" -> subscribers = whole(a, v, 1, 100);
                case "--seconds" -> seconds = whole(a, v, 1, 3600);
                default -> throw new IllegalArgumentException("unknown option '" + a + "'");
            }
        }
        if (archive && server.equals("prosody")) {
            throw new IllegalArgumentException("--archive: the archive in PostgreSQL is ejabberd's (--server ejabberd "
                    + "or cluster)");
        }
    }

    private static int whole(String option, String v, int min, int max) {
        try {
            int n = Integer.parseInt(v);
            if (n >= min && n <= max) {
                return n;
            }
        } catch (NumberFormatException e) {
            // below
        }
        throw new IllegalArgumentException(option + " '" + v + "': expected " + min + ".." + max);
    }

    private static double rate(String v) {
        try {
            double r = Double.parseDouble(v);
            if (r > 0 && r <= 100) {
                return r;
            }
        } catch (NumberFormatException e) {
            // below
        }
        throw new IllegalArgumentException("--hz '" + v + "': expected a rate in Hz, above 0 and at most 100");
    }

    private void run() throws Exception {
        SmackConfiguration.setDefaultReplyTimeout(20_000);
        XMPPTCPConnection.setUseStreamManagementDefault(false); // measure the protocol, not the ack traffic
        if (System.getProperty("sabot.root") == null && System.getenv("SABOT_ROOT") != null) {
            System.setProperty("sabot.root", System.getenv("SABOT_ROOT"));
        }
        boolean cluster = server.equals("cluster");
        PrivateXmppServer fixture = cluster ? PrivateXmppServer.ejabberdCluster() : PrivateXmppServer.of(
                PrivateXmppServer.Kind.valueOf(server.toUpperCase(Locale.ROOT)));
        if (archive) {
            fixture.sqlArchive();
        }
        Map<String, Object> figures = new LinkedHashMap<>();
        figures.put("robots", robots);
        figures.put("hz", hz);
        figures.put("server", server);
        figures.put("subscribers", subscribers);
        figures.put("seconds", seconds);
        figures.put("archive", archive);
        try (PrivateXmppServer s = fixture.start()) {
            Map<String, Long> measured = new LinkedHashMap<>();
            measured.put(cluster ? "node1" : "server", s.pid(1));
            if (cluster) {
                measured.put("node2", s.pid(2));
            }
            s.archiveDatabasePid().ifPresent(pid -> measured.put("database", pid));
            // on the cluster: robots on node 1, subscribers on node 2. On ejabberd explicit subscriptions, as the
            // workbench makes (TelemetryManager.follow): its +notify does not cross the nodes without the entity
            // capabilities in SQL, and even on one node now and then leaves a pair silent at a thousand robots
            TelemetryRun.Result r = TelemetryRun.run(s, new TelemetryRun.Options(robots, subscribers, hz, seconds, true,
                    1, cluster ? 2 : 1, !server.equals("prosody")), measured);
            long[] lat = r.latenciesNs();
            figures.put("sent", r.sent());
            figures.put("delivered", r.delivered());
            figures.put("lost", r.expected() - r.delivered());
            figures.put("delivered_pct", ControlMlBench.round(100.0 * r.delivered() / Math.max(1, r.expected())));
            figures.put("failed", r.failed());
            figures.put("p50_ms", lat.length == 0 ? "null" : ControlMlBench.round(ControlMlBench.ms(lat, 0.5)));
            figures.put("p99_ms", lat.length == 0 ? "null" : ControlMlBench.round(ControlMlBench.ms(lat, 0.99)));
            if (archive) {
                long archived = archivedValues(s);
                figures.put("sent_total", r.sentTotal());
                figures.put("archived", archived);
            }
            r.cpuPct().forEach((name, pct) -> figures.put(name + "_cpu_pct", ControlMlBench.round(pct)));
            r.rssMb().forEach((name, mb) -> figures.put(name + "_rss_mb", ControlMlBench.round(mb)));
            figures.put("client_cpu_pct", ControlMlBench.round(r.clientCpuPct()));
            figures.put("setup_s", ControlMlBench.round(r.setupS()));
            System.out.printf(Locale.ROOT, "[bench] fleet: %d robots x %s Hz on %s%s: sent %d, delivered %d of %d "
                    + "(%.2f %%), p50 %s ms, p99 %s ms%s%n", robots, hz, server, archive ? " with the archive" : "", r
                            .sent(), r.delivered(), r.expected(), 100.0 * r.delivered() / Math.max(1, r.expected()),
                    figures.get("p50_ms"), figures.get("p99_ms"), archive ? ", archived " + figures.get("archived")
                            + " of " + r.sentTotal() + " values sent in the run" : "");
        }
        ControlMlBench.printJson(figures);
    }

    /**
     * The telemetry values in the archive: distinct (device, id) of its telemetry rows (a value ejabberd refused with
     * its publish-options and the client sent again is one value, two rows). The archive writes every 200 ms, in
     * another process: counted again every second until the count stays the same (at most 30 s).
     */
    private static long archivedValues(PrivateXmppServer s) throws Exception {
        String sql = "SELECT count(DISTINCT (device, cm_id)) FROM sabot_archive WHERE kind = 'telemetry'";
        String last = "";
        String now = String.join("", s.archiveSql(sql));
        long settle = System.nanoTime() + TimeUnit.SECONDS.toNanos(30);
        while (!now.equals(last) && System.nanoTime() < settle) {
            last = now;
            new CountDownLatch(1).await(1, TimeUnit.SECONDS);
            now = String.join("", s.archiveSql(sql));
        }
        return Long.parseLong(now.strip());
    }
}
