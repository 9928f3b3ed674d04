package sabot.fleet.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicLong;

import org.jivesoftware.smack.ConnectionListener;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.Tag;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;
import org.jxmpp.jid.EntityBareJid;

import sabot.controlml.AccessPolicy;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.TelemetryPublication;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.fleet.AccessRules;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * A cluster node killed under load (docs/CLUSTER.md): {@value #ROBOTS} robots on node 1 publish their position at
 * {@value #HZ} Hz to an operator on node 2, who sends them a goal every {@value #COMMAND_MS} ms; node 1 is killed
 * ({@code kill -9}). Every robot logs in again through node 2 (as the product's session does on its next attempt,
 * proven on the product in {@code tests/sabot.system.tests} {@code ClusterFailoverTest}); its telemetry reaches the
 * operator again without the operator doing anything (its subscriptions are the cluster's); and no goal is applied
 * twice: each goal the operator saw taken was applied exactly once, each that failed (node 1 gone with it, the robot
 * not back yet) at most once. The sessions of node 1 die with it: nothing to resume on node 2.
 */
@Tag("ejabberd")
class ClusterUnderLoadTest {

    static final int ROBOTS = 40;
    static final double HZ = 1;
    static final long COMMAND_MS = 20;
    static final long TIMEOUT_S = 30;
    private static final String PASSWORD = "load-pw";

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.ejabberdCluster().sqlArchive();

    /** A robot under load: its account, the goals it applied (by the goal's x: one per command), its connection. */
    private static final class Robot {
        final String name;
        final EntityBareJid jid;
        final Map<Double, AtomicInteger> applied = new ConcurrentHashMap<>();
        volatile XMPPTCPConnection connection;
        volatile TelemetryPublication publication;
        final CountDownLatch back = new CountDownLatch(1);

        Robot(String name, EntityBareJid jid) {
            this.name = name;
            this.jid = jid;
        }

        /** Logs in through a node, answers goals under the lab's roles, publishes its position. */
        void login(int node) throws Exception {
            XMPPTCPConnection c = XMPP.connect(XMPP.configuration(node, name, PrivateXmppServer.DOMAIN, PASSWORD)
                    .setResource("onboard").build());
            ControlMlManager cm = ControlMlManager.getInstanceFor(c);
            cm.setAccessPolicy(AccessRules.labGroups().on(c));
            cm.onSet(Resources.GOAL, (requester, goal) -> {
                applied.computeIfAbsent(goal.pose().x(), x -> new AtomicInteger()).incrementAndGet();
                return Outcome.done();
            });
            AtomicLong tick = new AtomicLong();
            publication = cm.telemetry().publish(Resources.POSITION, () -> new PoseEstimate(Instant.now(), new Pose2D(
                    tick.incrementAndGet(), 0, 0), PoseCovariance.diagonal(0.01, 0.01, 0.01)), HZ);
            connection = c;
        }
    }

    @Test
    void aNodeKilledUnderLoadLosesNoRobotAndAppliesNoCommandTwice() throws Exception {
        EntityBareJid operatorJid = XMPP.register("load-operator", PrivateXmppServer.DOMAIN, PASSWORD);
        XMPP.grant(operatorJid, Role.OPERATOR);
        XMPPTCPConnection operator = XMPP.connect(XMPP.configuration(2, "load-operator", PrivateXmppServer.DOMAIN,
                PASSWORD).build());
        List<Robot> robots = new ArrayList<>();
        for (int i = 0; i < ROBOTS; i++) {
            String name = String.format(Locale.ROOT, "load-%02d", i);
            Robot r = new Robot(name, XMPP.register(name, PrivateXmppServer.DOMAIN, PASSWORD));
            XMPP.enrolRobot(r.jid);
            r.login(1);
            robots.add(r);
        }
        for (Robot r : robots) {
            AccessPolicy policy = ControlMlManager.getInstanceFor(r.connection).accessPolicy();
            FleetOnServerTest.awaitRole(Roster.getInstanceFor(r.connection), policy, operator, Role.OPERATOR);
        }
        // the operator follows every robot's position (explicit subscriptions: the cluster's, they outlive node 1)
        ControlMlManager op = ControlMlManager.getInstanceFor(operator);
        op.setRequestTimeout(Duration.ofSeconds(2));
        Map<EntityBareJid, Long> lastItem = new ConcurrentHashMap<>();
        op.telemetry().addListener(Resources.POSITION, (device, pose) -> lastItem.put(device, System.nanoTime()));
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);
        for (Robot r : robots) {
            Outcome<Void> followed;
            do {
                followed = op.telemetry().follow(r.jid, Resources.POSITION);
                assertTrue(System.nanoTime() < deadline, "never followed " + r.jid + ": " + followed);
            } while (!followed.isSuccess()); // item-not-found until the robot's first publication
        }

        // a goal every COMMAND_MS ms, round the fleet; each with its own x
        Map<Double, Robot> sentTo = new ConcurrentHashMap<>();
        Map<Double, Boolean> taken = new ConcurrentHashMap<>();
        Map<String, Integer> why = new ConcurrentHashMap<>(); // the failures' reasons, for the report
        AtomicBoolean commanding = new AtomicBoolean(true);
        ExecutorService threads = Executors.newFixedThreadPool(4);
        threads.execute(() -> {
            for (int seq = 1; commanding.get(); seq++) {
                Robot r = robots.get(seq % ROBOTS);
                double x = seq;
                sentTo.put(x, r);
                threads.execute(() -> {
                    Outcome<Goal> o = op.set(r.connection.getUser(), Resources.GOAL, new Goal(new Pose2D(x, 0, 0),
                            0.1, 0.1));
                    taken.put(x, o.isSuccess());
                    if (!o.isSuccess()) {
                        why.merge(String.valueOf(o.errorOrNull()).replaceAll("[0-9]+", "N"), 1, Integer::sum);
                    }
                });
                try {
                    Thread.sleep(COMMAND_MS); // the operator's pace: the load, not a synchronisation
                } catch (InterruptedException e) {
                    return;
                }
            }
        });
        // every robot logs in again through node 2 as soon as node 1 drops it
        ExecutorService relogin = Executors.newFixedThreadPool(4);
        for (Robot r : robots) {
            r.connection.addConnectionListener(new ConnectionListener() {
                @Override
                public void connectionClosedOnError(Exception e) {
                    relogin.execute(() -> {
                        r.publication.close();
                        for (long end = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S); System
                                .nanoTime() < end;) {
                            try {
                                r.login(2);
                                r.back.countDown();
                                return;
                            } catch (Exception again) {
                                // node 2 busy with the others: the next attempt at once, as the product's session
                            }
                        }
                    });
                }
            });
        }
        waitForItemsAfter(robots, lastItem, System.nanoTime(), "before the kill");

        long t0 = System.nanoTime();
        XMPP.killNode(1);
        for (Robot r : robots) {
            assertTrue(r.back.await(TIMEOUT_S, TimeUnit.SECONDS), r.jid + " not back through node 2");
        }
        long allBack = System.nanoTime() - t0;
        waitForItemsAfter(robots, lastItem, t0, "after the kill");
        long telemetryBack = System.nanoTime() - t0;
        // commands go on to the robots back on node 2 for a while, then stop
        int takenBefore = (int) taken.values().stream().filter(b -> b).count();
        long until = System.nanoTime() + TimeUnit.SECONDS.toNanos(2);
        while (System.nanoTime() < until || taken.values().stream().filter(b -> b).count() < takenBefore + ROBOTS) {
            assertTrue(System.nanoTime() - t0 < TimeUnit.SECONDS.toNanos(2 * TIMEOUT_S), "goals not taken again: "
                    + taken.size() + " answered of " + sentTo.size() + " sent, " + robots.stream().mapToInt(
                            r -> r.applied.size()).sum() + " applied, failures " + why);
            Thread.sleep(20); // the command thread's progress, in this JVM but on the network: polled
        }
        commanding.set(false);
        threads.shutdown();
        assertTrue(threads.awaitTermination(TIMEOUT_S, TimeUnit.SECONDS));

        List<String> twice = new ArrayList<>();
        List<String> lost = new ArrayList<>();
        int failed = 0;
        for (Map.Entry<Double, Robot> e : sentTo.entrySet()) {
            AtomicInteger n = e.getValue().applied.get(e.getKey());
            int applied = n == null ? 0 : n.get();
            if (applied > 1) {
                twice.add(e.getValue().name + " x=" + e.getKey() + " applied " + applied + " times");
            }
            Boolean ok = taken.get(e.getKey());
            if (Boolean.TRUE.equals(ok) && applied != 1) {
                lost.add(e.getValue().name + " x=" + e.getKey() + " taken but applied " + applied + " times");
            }
            if (!Boolean.TRUE.equals(ok)) {
                failed++;
            }
        }
        assertEquals(List.of(), twice, "goals applied twice");
        assertEquals(List.of(), lost, "goals the operator saw taken and the robot did not apply");
        System.out.printf(Locale.ROOT, "[figure] ejabberd cluster under load (%d robots at %.0f Hz, a goal every %d ms):"
                + " node 1 killed to all robots logged in through node 2: %d ms; to telemetry from all at the operator: "
                + "%d ms; %d goals sent, %d failed (none applied twice)%n", ROBOTS, HZ, COMMAND_MS, TimeUnit.NANOSECONDS
                        .toMillis(allBack), TimeUnit.NANOSECONDS.toMillis(telemetryBack), sentTo.size(), failed);
        relogin.shutdown();
        for (Robot r : robots) {
            r.publication.close();
        }
    }

    /** Waits until the operator has had a telemetry item from every robot after {@code since} (nanoTime). */
    private static void waitForItemsAfter(List<Robot> robots, Map<EntityBareJid, Long> lastItem, long since,
            String when) throws InterruptedException {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);
        while (true) {
            List<String> silent = robots.stream().filter(r -> lastItem.getOrDefault(r.jid, Long.MIN_VALUE) <= since)
                    .map(r -> r.name).toList();
            if (silent.isEmpty()) {
                return;
            }
            assertTrue(System.nanoTime() < deadline, "no telemetry " + when + " from " + silent);
            Thread.sleep(20); // items arrive on Smack's threads; the set is polled
        }
    }
}
