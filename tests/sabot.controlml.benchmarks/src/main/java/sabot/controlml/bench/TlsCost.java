package sabot.controlml.bench;

import static sabot.controlml.bench.ControlMlBench.ms;
import static sabot.controlml.bench.ControlMlBench.round;

import java.time.Instant;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.FullJid;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * What TLS and SCRAM cost ({@code ./sabot bench controlml --tls}): two private servers of one kind in the same run, one
 * requiring TLS (the lab CA, as every Sabot client) and one on plain TCP ({@code sabot-xmpp start --tls off}, which
 * exists for this comparison only), both with SCRAM-SHA-256.
 * <ol>
 * <li>a {@code cm.position} get round trip, a pair of clients on each server, requests alternating between them;</li>
 * <li>a login (TCP, STARTTLS and certificate check, SCRAM-SHA-256, resource binding), alternating between them;</li>
 * <li>{@code robots} robots logged in on the TLS server, the server restarted: the time until every robot is logged
 * in again, each retrying at once on a connection of its own (as the onboard product's session does, without its
 * back-off).</li>
 * </ol>
 * Clients and servers share the CPUs (two servers: no CPU of its own for each).
 */
final class TlsCost {

    private final PrivateXmppServer.Kind kind;
    private final int requests;
    private final int warmup;
    private final int logins;
    private final int robots;

    TlsCost(PrivateXmppServer.Kind kind, int requests, int warmup, int logins, int robots) {
        this.kind = kind;
        this.requests = requests;
        this.warmup = warmup;
        this.logins = logins;
        this.robots = robots;
    }

    void run(Map<String, Object> figures) throws Exception {
        try (PrivateXmppServer tls = PrivateXmppServer.of(kind).start();
                PrivateXmppServer plain = PrivateXmppServer.of(kind).plainTcp().start()) {
            figures.put("cpu_layout", "shared (two servers)");
            roundTrips(tls, plain, figures);
            logins(tls, plain, figures);
            reconnection(tls, figures);
        }
    }

    private record Pair(ControlMlManager client, FullJid robot) {
    }

    private static Pair pair(PrivateXmppServer server, PoseEstimate pose) throws Exception {
        XMPPTCPConnection workbench = server.login("tls-wb");
        XMPPTCPConnection robot = server.login("tls-robot");
        ControlMlManager device = ControlMlManager.getInstanceFor(robot);
        device.setAccessPolicy(j -> j.asBareJid().equals(workbench.getUser().asBareJid()) ? Role.OBSERVER
                : Role.NONE);
        device.onGet(Resources.POSITION, (r, q) -> Outcome.success(pose));
        return new Pair(ControlMlManager.getInstanceFor(workbench), robot.getUser());
    }

    private void roundTrips(PrivateXmppServer tls, PrivateXmppServer plain, Map<String, Object> figures)
            throws Exception {
        PoseEstimate pose = new PoseEstimate(Instant.parse("2026-11-21T10:15:30.123456Z"), new Pose2D(1.25, -3.5,
                0.785), new PoseCovariance(0.01, 0.001, -0.0002, 0.02, 0.0003, 0.0004));
        Pair[] pairs = { pair(tls, pose), pair(plain, pose) };
        long[][] t = new long[2][requests];
        for (int i = -warmup; i < requests; i++) {
            for (int k = 0; k < 2; k++) {
                int which = (i + k) % 2 == 0 ? 0 : 1; // each goes first every other time
                long start = System.nanoTime();
                Outcome<PoseEstimate> got = pairs[which].client().get(pairs[which].robot(), Resources.POSITION);
                long elapsed = System.nanoTime() - start;
                if (!got.isSuccess() || !pose.equals(got.orElseThrow())) {
                    throw new IllegalStateException("cm.position get failed: " + got);
                }
                if (i >= 0) {
                    t[which][i] = elapsed;
                }
            }
        }
        Arrays.sort(t[0]);
        Arrays.sort(t[1]);
        System.out.printf(Locale.ROOT, "[bench] %s cm.position get over TLS   p50 %.3f ms  p99 %.3f ms%n", name(),
                ms(t[0], 0.5), ms(t[0], 0.99));
        System.out.printf(Locale.ROOT, "[bench] %s cm.position get, plain TCP p50 %.3f ms  p99 %.3f ms  (TLS/plain "
                + "p50 %.2f, p99 %.2f; %d requests each)%n", name(), ms(t[1], 0.5), ms(t[1], 0.99), ms(t[0], 0.5) / ms(
                        t[1], 0.5), ms(t[0], 0.99) / ms(t[1], 0.99), requests);
        figures.put("get_tls_p50_ms", round(ms(t[0], 0.5)));
        figures.put("get_tls_p99_ms", round(ms(t[0], 0.99)));
        figures.put("get_plain_p50_ms", round(ms(t[1], 0.5)));
        figures.put("get_plain_p99_ms", round(ms(t[1], 0.99)));
        figures.put("get_tls_to_plain_p50", round(ms(t[0], 0.5) / ms(t[1], 0.5)));
    }

    private void logins(PrivateXmppServer tls, PrivateXmppServer plain, Map<String, Object> figures)
            throws Exception {
        PrivateXmppServer[] servers = { tls, plain };
        for (PrivateXmppServer s : servers) {
            s.register("tls-login", PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD);
        }
        long[][] t = new long[2][logins];
        for (int i = -Math.min(20, logins); i < logins; i++) {
            for (int k = 0; k < 2; k++) {
                int which = (i + k) % 2 == 0 ? 0 : 1;
                XMPPTCPConnection c = new XMPPTCPConnection(servers[which].configuration("tls-login",
                        PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD).setResource("login-" + i)
                        .setSendPresence(false).build());
                long start = System.nanoTime();
                c.connect().login();
                long elapsed = System.nanoTime() - start;
                if (which == 0 && !"SCRAM-SHA-256".equals(c.getUsedSaslMechansism())) {
                    throw new IllegalStateException("logged in with " + c.getUsedSaslMechansism());
                }
                c.instantShutdown();
                if (i >= 0) {
                    t[which][i] = elapsed;
                }
            }
        }
        Arrays.sort(t[0]);
        Arrays.sort(t[1]);
        System.out.printf(Locale.ROOT, "[bench] %s login (TCP, STARTTLS, SCRAM-SHA-256, bind) p50 %.1f ms  p99 %.1f ms;"
                + " plain TCP p50 %.1f ms  p99 %.1f ms (%d logins each)%n", name(), ms(t[0], 0.5), ms(t[0], 0.99), ms(
                        t[1], 0.5), ms(t[1], 0.99), logins);
        figures.put("login_tls_p50_ms", round(ms(t[0], 0.5)));
        figures.put("login_tls_p99_ms", round(ms(t[0], 0.99)));
        figures.put("login_plain_p50_ms", round(ms(t[1], 0.5)));
        figures.put("login_plain_p99_ms", round(ms(t[1], 0.99)));
    }

    private void reconnection(PrivateXmppServer server, Map<String, Object> figures) throws Exception {
        ExecutorService pool = Executors.newFixedThreadPool(robots, Thread.ofPlatform().daemon().factory());
        try {
            Map<EntityBareJid, String> accounts = new LinkedHashMap<>();
            for (int i = 0; i < robots; i++) {
                accounts.put(JidCreate.entityBareFrom("storm-" + i + "@" + PrivateXmppServer.DOMAIN),
                        PrivateXmppServer.DEFAULT_PASSWORD);
            }
            server.registerAll(accounts);
            List<Future<?>> up = new ArrayList<>();
            for (int i = 0; i < robots; i++) {
                int n = i;
                up.add(pool.submit(() -> loginUntilDone(server, n, Long.MAX_VALUE)));
            }
            List<XMPPTCPConnection> online = new ArrayList<>();
            for (Future<?> f : up) {
                online.add((XMPPTCPConnection) f.get(120, TimeUnit.SECONDS));
            }
            long stop0 = System.nanoTime();
            server.stopServer();
            server.restart();
            long ready = System.nanoTime();
            List<Future<XMPPTCPConnection>> back = new ArrayList<>();
            long deadline = ready + TimeUnit.SECONDS.toNanos(120);
            for (int i = 0; i < robots; i++) {
                int n = i;
                back.add(pool.submit(() -> loginUntilDone(server, n, deadline)));
            }
            for (Future<XMPPTCPConnection> f : back) {
                online.add(f.get(180, TimeUnit.SECONDS));
            }
            long allBack = System.nanoTime();
            System.out.printf(Locale.ROOT, "[bench] %s %d robots logged in, server restarted (stop + start %.1f s): "
                    + "all logged in again %.1f s after the server was ready%n", name(), robots, (ready - stop0) / 1e9,
                    (allBack - ready) / 1e9);
            figures.put("reconnect_robots", robots);
            figures.put("reconnect_restart_s", round((ready - stop0) / 1e9));
            figures.put("reconnect_all_back_s", round((allBack - ready) / 1e9));
            for (XMPPTCPConnection c : online) {
                if (c.isConnected()) {
                    c.instantShutdown();
                }
            }
        } finally {
            pool.shutdownNow();
        }
    }

    /** Logs robot {@code n} in on a new connection per attempt until it succeeds or the deadline passes. */
    private static XMPPTCPConnection loginUntilDone(PrivateXmppServer server, int n, long deadline)
            throws Exception {
        while (true) {
            XMPPTCPConnection c = new XMPPTCPConnection(server.configuration("storm-" + n, PrivateXmppServer.DOMAIN,
                    PrivateXmppServer.DEFAULT_PASSWORD).setResource("onboard").build());
            try {
                c.connect().login();
                return c;
            } catch (Exception e) {
                c.instantShutdown();
                if (System.nanoTime() > deadline) {
                    throw new IllegalStateException("storm-" + n + " not back: " + e, e);
                }
                TimeUnit.MILLISECONDS.sleep(50); // the next attempt: a robot's retry, not a synchronisation
            }
        }
    }

    private String name() {
        return kind.name().toLowerCase(Locale.ROOT);
    }
}
