package sabot.fleet.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Instant;
import java.util.Arrays;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.ArrayBlockingQueue;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.ConnectionListener;
import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.roster.AbstractRosterListener;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smackx.ping.PingManager;
import org.junit.jupiter.api.MethodOrderer;
import org.junit.jupiter.api.Order;
import org.junit.jupiter.api.Tag;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.TestMethodOrder;
import org.junit.jupiter.api.extension.RegisterExtension;
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.EntityBareJid;

import sabot.controlml.AccessPolicy;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.PresenceLevel;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.TelemetryManager;
import sabot.controlml.TelemetryPublication;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.fleet.AccessRules;
import sabot.fleet.PresenceLevels;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * A fleet on a two-node ejabberd cluster (docs/CLUSTER.md): the robot on node 1 (127.0.0.1), the operator on node 2
 * (127.0.0.2). The accounts and the lab's groups are one Mnesia; roles, ControlML requests, presence levels and
 * telemetry (an explicit subscription: ejabberd's entity-capability cache is per node) cross the nodes. A node that
 * dies leaves the other serving, and the robot logs in again through it. Both nodes archive into one PostgreSQL
 * (docs/ARCHIVE.md).
 */
@Tag("ejabberd")
@TestMethodOrder(MethodOrderer.OrderAnnotation.class)
class EjabberdClusterTest {

    static final long TIMEOUT_S = 10;

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.ejabberdCluster().sqlArchive();

    private static final String PASSWORD = "cluster-pw";

    private static XMPPTCPConnection on(int node, String localpart) throws Exception {
        return XMPP.connect(XMPP.configuration(node, localpart, PrivateXmppServer.DOMAIN, PASSWORD).build());
    }

    /** A robot and an operator of the lab, the robot's roles read from its roster (node 1's view of the groups). */
    private record Pair(XMPPTCPConnection robot, XMPPTCPConnection operator, ControlMlManager robotManager,
            Goal[] goal) {
    }

    private static Pair pair(String robotName, String operatorName) throws Exception {
        EntityBareJid robotJid = XMPP.register(robotName, PrivateXmppServer.DOMAIN, PASSWORD);
        EntityBareJid operatorJid = XMPP.register(operatorName, PrivateXmppServer.DOMAIN, PASSWORD);
        XMPPTCPConnection robot = on(1, robotName);
        XMPPTCPConnection operator = on(2, operatorName);
        AccessPolicy policy = AccessRules.labGroups().on(robot);
        Goal[] goal = FleetOnServerTest.goalDevice(robot, policy);
        ControlMlManager cm = ControlMlManager.getInstanceFor(robot);
        // the lab's administrator, through node 1's admin API, while both are online: the groups are the cluster's
        XMPP.enrolRobot(robotJid);
        XMPP.grant(operatorJid, Role.OPERATOR);
        FleetOnServerTest.awaitRole(Roster.getInstanceFor(robot), policy, operator, Role.OPERATOR);
        awaitOnline(operator, robot);
        return new Pair(robot, operator, cm, goal);
    }

    /**
     * Waits until {@code watcher} sees {@code device} online, as a workbench commands only the robots it sees online:
     * the session table reaches the other node a moment after the login (a request routed there before is answered
     * {@code service-unavailable}, "User session not found").
     */
    static void awaitOnline(XMPPTCPConnection watcher, XMPPTCPConnection device) throws InterruptedException {
        Roster roster = Roster.getInstanceFor(watcher);
        BareJid bare = device.getUser().asBareJid();
        CountDownLatch online = new CountDownLatch(1);
        roster.addRosterListener(new AbstractRosterListener() {
            @Override
            public void presenceChanged(Presence presence) {
                if (presence.getFrom().asBareJid().equals(bare) && presence.isAvailable()) {
                    online.countDown();
                }
            }
        });
        if (roster.getPresence(bare).isAvailable()) {
            online.countDown();
        }
        assertTrue(online.await(TIMEOUT_S, TimeUnit.SECONDS), watcher.getUser() + " never saw " + bare + " online");
    }

    @Test
    @Order(1)
    void aRobotOnOneNodeIsCommandedAndWatchedFromTheOther() throws Exception {
        Pair p = pair("cl-robot", "cl-operator");
        ControlMlManager operator = ControlMlManager.getInstanceFor(p.operator());

        // a command across the nodes
        Goal target = new Goal(new Pose2D(2, 3, 0), 0.1, 0.1);
        Outcome<Goal> taken = operator.set(p.robot().getUser(), Resources.GOAL, target);
        assertTrue(taken.isSuccess(), String.valueOf(taken));
        assertEquals(target, p.goal()[0]);
        long[] rtt = new long[200];
        for (int i = 0; i < rtt.length; i++) {
            long t0 = System.nanoTime();
            assertEquals(target, operator.get(p.robot().getUser(), Resources.GOAL).orElseThrow());
            rtt[i] = System.nanoTime() - t0;
        }
        Arrays.sort(rtt);
        System.out.printf(Locale.ROOT, "[figure] ejabberd cluster: cm.goal get from node 2 to a robot on node 1: p50 "
                + "%.2f ms, p99 %.2f ms (%d requests)%n", rtt[rtt.length / 2] / 1e6, rtt[rtt.length * 99 / 100] / 1e6,
                rtt.length);
        // each node archived what its clients sent, into the one database (docs/ARCHIVE.md): the goal through node
        // 2, its answer through node 1 (in the order they were taken: each node writes its rows when it will, so the
        // rows' numbers do not say it); the archive writes every 200 ms, in another process: polled
        String sql = "SELECT kind, node FROM sabot_archive WHERE device = '" + p.robot().getUser().asBareJid()
                + "' AND res = 'cm.goal' AND kind IN ('set', 'result') ORDER BY at, seq LIMIT 2";
        List<String> rows = XMPP.archiveSql(sql);
        for (long end = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S); rows.size() < 2
                && System.nanoTime() < end; rows = XMPP.archiveSql(sql)) {
            Thread.sleep(50);
        }
        assertEquals(2, rows.size(), "the goal and its answer not archived: " + rows);
        assertTrue(rows.get(0).startsWith("set|") && rows.get(0).endsWith("@127.0.0.2"), rows.get(0));
        assertTrue(rows.get(1).startsWith("result|") && rows.get(1).endsWith("@127.0.0.1"), rows.get(1));

        // its presence level across the nodes
        Roster roster = Roster.getInstanceFor(p.operator());
        BareJid robotBare = p.robot().getUser().asBareJid();
        CountDownLatch busy = new CountDownLatch(1);
        roster.addRosterListener(new AbstractRosterListener() {
            @Override
            public void presenceChanged(Presence presence) {
                if (presence.getFrom().asBareJid().equals(robotBare) && PresenceLevels.of(presence)
                        == PresenceLevel.BUSY) {
                    busy.countDown();
                }
            }
        });
        p.robot().sendStanza(PresenceLevels.presenceFor(p.robot(), MissionState.RUNNING, false));
        assertTrue(busy.await(TIMEOUT_S, TimeUnit.SECONDS), "the robot's busy presence never reached node 2: "
                + roster.getPresence(robotBare));
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);

        // telemetry across the nodes: an explicit subscription to the robot's node
        BlockingQueue<PoseEstimate> poses = new ArrayBlockingQueue<>(100);
        TelemetryManager.getInstanceFor(p.operator()).addListener(Resources.POSITION, (device, pose) -> poses.offer(
                pose));
        int[] tick = { 0 };
        try (TelemetryPublication pub = p.robotManager().telemetry().publish(Resources.POSITION,
                () -> new PoseEstimate(Instant.now(), new Pose2D(++tick[0], 0, 0), PoseCovariance.diagonal(0.01,
                        0.01, 0.01)), 20)) {
            Outcome<Void> followed;
            do {
                followed = operator.telemetry().follow(p.robot().getUser().asEntityBareJidOrThrow(),
                        Resources.POSITION);
                assertTrue(System.nanoTime() < deadline, "never followed: " + followed);
            } while (!followed.isSuccess()); // item-not-found until the robot's first publication made the node
            for (int i = 0; i < 5; i++) {
                assertNotNull(poses.poll(TIMEOUT_S, TimeUnit.SECONDS), "telemetry item " + i + " did not cross");
            }
        }
    }

    /** Last: node 1 stays dead. The lab's administration goes on through node 2's admin API. */
    @Test
    @Order(2)
    void aNodeThatDiesLeavesTheOtherServingAndTheRobotLogsInThroughIt() throws Exception {
        Pair p = pair("cl-robot-2", "cl-operator-2");
        CountDownLatch lost = new CountDownLatch(1);
        p.robot().addConnectionListener(new ConnectionListener() {
            @Override
            public void connectionClosedOnError(Exception e) {
                lost.countDown();
            }

            @Override
            public void connectionClosed() {
                lost.countDown();
            }
        });
        long t0 = System.nanoTime();
        XMPP.killNode(1);
        assertTrue(lost.await(TIMEOUT_S, TimeUnit.SECONDS), "the robot on node 1 never noticed");
        assertTrue(PingManager.getInstanceFor(p.operator()).pingMyServer(true, 5_000), "node 2 stopped serving");

        // the robot again, through node 2: the same account, its groups, and the operator's commands
        XMPPTCPConnection again = on(2, "cl-robot-2");
        AccessPolicy policy = AccessRules.labGroups().on(again);
        ControlMlManager cm = ControlMlManager.getInstanceFor(again);
        cm.setAccessPolicy(policy);
        cm.onGet(Resources.GOAL, (r, q) -> Outcome.success(p.goal()[0]));
        FleetOnServerTest.awaitRole(Roster.getInstanceFor(again), policy, p.operator(), Role.OPERATOR);
        assertEquals(p.goal()[0], ControlMlManager.getInstanceFor(p.operator()).get(again.getUser(), Resources.GOAL)
                .orElseThrow());
        System.out.printf(Locale.ROOT, "[figure] ejabberd cluster: node 1 killed to its robot answering through node "
                + "2: %d ms (a client logging in again at once)%n", TimeUnit.NANOSECONDS.toMillis(System.nanoTime()
                        - t0));
        assertTrue(XMPP.pid(1) == 0 && XMPP.pid(2) != 0);
        // administered through the surviving node: a new account and a role for it
        EntityBareJid late = XMPP.register("cl-late", PrivateXmppServer.DOMAIN, PASSWORD);
        XMPP.grant(late, Role.OBSERVER);
        XMPPTCPConnection observer = on(2, "cl-late");
        FleetOnServerTest.awaitRole(Roster.getInstanceFor(again), policy, observer, Role.OBSERVER);
    }
}
