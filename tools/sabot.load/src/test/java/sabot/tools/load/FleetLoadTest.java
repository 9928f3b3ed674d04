package sabot.tools.load;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.jxmpp.jid.EntityBareJid;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.GridMap;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.PoseEstimate;
import sabot.model.geometry.Pose2D;
import sabot.model.map.OccupancyGrid;
import sabot.testsupport.xmpp.PrivateXmppServer;

/** The load robots are real ControlML endpoints on a real Prosody, with the robot's access rules. */
class FleetLoadTest {

    static PrivateXmppServer server;
    static FleetLoad load;
    static EntityBareJid operator;

    @BeforeAll
    static void start() throws Exception {
        FleetLoad.setUpSmack();
        server = PrivateXmppServer.prosody().start();
        operator = server.register("operator", PrivateXmppServer.DOMAIN, "operator-pw");
        load = FleetLoad.start(server, 3, "load-", "robot-pw", operator, 10, 10, 1, PrivateXmppServer.repositoryRoot()
                .resolve("onboard-bridge/maps/lab.yaml"));
    }

    @AfterAll
    static void stop() {
        if (load != null) {
            load.close();
        }
        if (server != null) {
            server.close();
        }
    }

    @Test
    void theOperatorGetsAndSetsAndReceivesTelemetryAfterSubscribing() throws Exception {
        XMPPTCPConnection wb = new XMPPTCPConnection(server.configuration("operator", PrivateXmppServer.DOMAIN,
                "operator-pw").setResource("wb").build());
        Map<EntityBareJid, PoseEstimate> poses = new ConcurrentHashMap<>();
        CountDownLatch all = new CountDownLatch(3);
        ControlMlManager cm = ControlMlManager.getInstanceFor(wb);
        cm.telemetry().addListener(Resources.POSITION, (device, p) -> {
            if (poses.put(device, p) == null) {
                all.countDown();
            }
        });
        // the workbench's rule: approve the subscriptions of the robots it follows (they subscribe back)
        sabot.fleet.SubscriptionGate.onWorkbench(wb);
        try {
            wb.connect().login();
            List<EntityBareJid> robots = load.jids();
            assertEquals("load-01@sabot.local", robots.get(0).toString());
            Following.follow(wb, robots);
            assertTrue(all.await(30, TimeUnit.SECONDS), "telemetry from every robot: " + poses.keySet());
            EntityBareJid first = robots.get(0);
            // the pose moves on the robot's circle (inside the lab)
            Pose2D p = poses.get(first).pose();
            assertTrue(p.x() > 0 && p.x() < 12 && p.y() > 0 && p.y() < 9, p.toString());
            var full = Roster.getInstanceFor(wb).getPresence(first).getFrom();
            GridMap map = cm.get(full, Resources.MAP).orElseThrow();
            assertEquals(120, map.width());
            assertEquals(90, map.height());
            assertEquals(0.1, map.resolution(), 1e-12);
            Outcome<Goal> none = cm.get(full, Resources.GOAL);
            assertFalse(none.isSuccess());
            assertEquals(ControlMlCondition.INVALID_STATE, none.errorOrNull().cmCondition());
            Goal g = new Goal(new Pose2D(2, 3, 0), 0.1, 0.2);
            assertTrue(cm.set(full, Resources.GOAL, g).isSuccess());
            assertEquals(g, cm.get(full, Resources.GOAL).orElseThrow());
            assertEquals(MissionState.RUNNING, cm.get(full, Resources.MISSION).orElseThrow().state());
        } finally {
            wb.disconnect();
        }
    }

    @Test
    void aStrangerIsRefused() throws Exception {
        server.register("stranger", PrivateXmppServer.DOMAIN, "stranger-pw");
        XMPPTCPConnection s = new XMPPTCPConnection(server.configuration("stranger", PrivateXmppServer.DOMAIN,
                "stranger-pw").build());
        try {
            s.connect().login();
            var robot = org.jxmpp.jid.impl.JidCreate.fullFrom(load.jids().get(1) + "/onboard");
            Outcome<PoseEstimate> o = ControlMlManager.getInstanceFor(s).get(robot, Resources.POSITION);
            assertFalse(o.isSuccess());
            assertEquals(ControlMlCondition.ACCESS_DENIED, o.errorOrNull().cmCondition());
        } finally {
            s.disconnect();
        }
    }

    @Test
    void theMapIsHalvedTakingTheMostOccupiedCell() {
        OccupancyGrid g = OccupancyGrid.unknown(4, 2, 0.05, new Pose2D(1, 2, 0));
        g.set(0, 0, 0);
        g.set(1, 0, 0);
        g.set(0, 1, 0);
        g.set(1, 1, 100);
        GridMap h = FleetLoad.halved(g);
        assertEquals(2, h.width());
        assertEquals(1, h.height());
        assertEquals(0.1, h.resolution(), 1e-12);
        assertEquals(100, h.cells()[0]);
        assertEquals(-1, h.cells()[1]); // all unknown
        assertEquals(new Pose2D(1, 2, 0), h.origin());
    }
}
