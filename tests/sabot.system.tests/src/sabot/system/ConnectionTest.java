package sabot.system;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Arrays;
import java.util.Map;
import java.util.Random;
import java.util.TreeMap;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;

import org.jivesoftware.smack.packet.IQ;
import org.jivesoftware.smack.packet.StanzaError;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlIQ;
import sabot.controlml.ControlMlManager;
import sabot.controlml.ControlMlType;
import sabot.controlml.Outcome;
import sabot.controlml.RequestIdGenerator;
import sabot.controlml.Resources;
import sabot.controlml.TelemetryWatcher;
import sabot.controlml.payload.FileChunk;
import sabot.controlml.payload.FileQuery;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.TaskInfo;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.net.SilentRelay;
import sabot.testsupport.xmpp.PrivateXmppServer;
import sabot.testsupport.robot.SimProcess;

/**
 * Proofs 4 and 7: the XMPP side of a running robot. The server stopped mid-drive stops the robot, which reconnects
 * when the server is back and stays still until a new command; the remote FS works through the running product while
 * a second workbench watches the robot's telemetry. Each running task is reported with the task bundle that provides it.
 */
class ConnectionTest extends RigTest {

    static final double[] START = CORRIDOR_MIDDLE;

    @Test
    void robotStopsWhenTheServerGoesAwayAndReconnectsWithoutMoving(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, START, new String[0], "controlml.reconnectMin = 0.2\n"
                + "controlml.reconnectMax = 1\n")) {
            assertTrue(rig.operator.set(rig.robot, Resources.GOAL, new Goal(new Pose2D(9.5, 1.0, 0), 0.15, 0.3))
                    .isSuccess(), rig.onboard.output());
            SimProcess.Truth moving = awaitSpeed(rig.sim, 0.2, 20);

            xmpp.stopServer();
            SimProcess.Truth stopped = awaitStandstill(rig.sim, 5);
            assertTrue(stopped.t() - moving.t() < 1.0 + moving.v() / A_MAX, "stopped after "
                    + (stopped.t() - moving.t()) + " s");
            rig.onboard.await(l -> l.contains("XMPP connection lost while moving"), "reporting why it stopped");

            xmpp.restart();
            rig.onboard.awaitCount(l -> l.contains("XMPP session online"), 2, "saying the session is back");
            XMPPTCPConnection operator = xmpp.connect(xmpp.configuration(RobotRig.OPERATOR, PrivateXmppServer.DOMAIN,
                    PrivateXmppServer.DEFAULT_PASSWORD).build());
            ControlMlManager cm = ControlMlManager.getInstanceFor(operator);
            MissionStatus mission = cm.get(rig.robot, Resources.MISSION).orElseThrow();
            assertEquals(MissionState.FAILED, mission.state(), mission.toString());
            assertTrue(mission.detail().contains("connection lost"), mission.toString());

            SimProcess.Truth later = awaitSimTime(rig.sim, 1.5);
            assertTrue(later.distanceTo(stopped.x(), stopped.y()) < 0.01, "moved without a new command: " + later);

            assertTrue(cm.set(rig.robot, Resources.GOAL, new Goal(new Pose2D(6.0, 1.0, 0), 0.15, 0.3)).isSuccess());
            awaitSpeed(rig.sim, 0.1, 20);
        }
    }

    /**
     * A network that goes silent mid-mission — nothing passes, nothing is closed, as a Wi-Fi dead spot — stops the
     * robot within two liveness intervals (1 s each), the check's quarter interval and the braking; the robot says
     * why, reconnects once traffic passes again, and stands still until a new command. A goal sent into the silence,
     * which the operator saw time out, reaches the robot on stream resumption and is refused as stale.
     */
    @Test
    void robotBrakesWhenTheLinkGoesSilentAndStandsStillWhenItComesBack(@TempDir Path dir) throws Exception {
        try (SilentRelay relay = new SilentRelay(xmpp.port());
                RobotRig rig = RobotRig.start(xmpp, relay.port(), dir, START, START, new String[0],
                        "controlml.reconnectMin = 0.2\ncontrolml.reconnectMax = 1\ncontrolml.staleCommandAfter = 2\n")) {
            assertTrue(rig.operator.set(rig.robot, Resources.GOAL, new Goal(new Pose2D(9.5, 1.0, 0), 0.15, 0.3))
                    .isSuccess(), rig.onboard.output());
            SimProcess.Truth moving = awaitSpeed(rig.sim, 0.2, 20);

            relay.silence();
            double liveness = 1.0;
            double bound = 2.25 * liveness + moving.v() / A_MAX + 0.3;
            SimProcess.Truth stopped = awaitStandstill(rig.sim, bound + 5);
            System.out.printf(java.util.Locale.ROOT, "[figure] silent link to standstill: %.2f s from %.2f m/s "
                    + "(liveness %.1f s)%n", stopped.t() - moving.t(), moving.v(), liveness);
            assertTrue(stopped.t() - moving.t() <= bound, "stopped " + (stopped.t() - moving.t()) + " s after the "
                    + "link went silent, bound " + bound + " s");
            rig.onboard.await(l -> l.contains("XMPP connection lost while moving (connection silent for"),
                    "reporting why it stopped");

            // The operator sends a new goal into the silence: the server holds it for the robot's session, and the
            // operator's request times out (as the workbench's does, here after 3 s) before the link is back: older
            // than the robot's staleCommandAfter (2 s) when it arrives.
            BlockingQueue<ControlMlElement> late = new LinkedBlockingQueue<>();
            rig.operatorConnection.addAsyncStanzaListener(iq -> late.add(((ControlMlIQ) iq).element()),
                    stanza -> stanza instanceof ControlMlIQ iq && iq.getType() == IQ.Type.error);
            ControlMlElement held = ControlMlElement.request(ControlMlType.SET, new RequestIdGenerator().next(),
                    "cm.goal", Resources.GOAL.codec().encode(new Goal(new Pose2D(9.5, 1.0, 0), 0.15, 0.3)));
            rig.operator.setRequestTimeout(Duration.ofSeconds(3));
            Outcome<ControlMlElement> timedOut = rig.operator.exchange(rig.robot, held);
            assertEquals(ControlMlCondition.TIMEOUT, timedOut.errorOrNull().cmCondition(), timedOut::toString);
            rig.operator.setRequestTimeout(Duration.ofSeconds(10));

            relay.resume();
            rig.onboard.awaitCount(l -> l.contains("XMPP session online"), 2, "saying the session is back");
            // the server delivers the held goal on stream resumption; the robot judges it by its send time
            ControlMlElement answer = late.poll(30, TimeUnit.SECONDS);
            assertTrue(answer != null && held.id().equals(answer.id()), () -> "no answer to the held goal: " + answer
                    + "\n" + rig.onboard.output());
            assertEquals(ControlMlCondition.STALE_COMMAND, answer.failure().cmCondition(), answer.toString());
            MissionStatus mission = rig.get(Resources.MISSION);
            assertEquals(MissionState.FAILED, mission.state(), mission.toString());
            assertTrue(mission.detail().contains("connection silent"), mission.toString());
            SimProcess.Truth later = awaitSimTime(rig.sim, 3);
            assertTrue(later.distanceTo(stopped.x(), stopped.y()) < 0.01, "moved without a new command: " + later);
        }
    }

    @Test
    void everyTaskIsReportedWithTheTaskBundleThatProvidesIt(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, START, new String[0], "")) {
            Map<String, String> bundles = new TreeMap<>();
            for (TaskInfo t : rig.operator.get(rig.robot, Resources.TASKS).orElseThrow().tasks()) {
                assertEquals("active", t.state(), t.toString());
                assertTrue(t.version().matches("\\d+\\.\\d+\\.\\d+\\.\\S+"), t.toString());
                bundles.put(t.name(), t.bundle());
            }
            String motion = "sabot.onboard.motion";
            assertEquals(Map.of("bus", motion, "localizer", motion, "planner", motion, "tracker", motion, "teleop",
                    motion, "motion", motion, "controlml", "sabot.onboard.controlml", "remotefs",
                    "sabot.onboard.remotefs"), bundles);
        }
    }

    @Test
    void remoteFileSystemWorksWhileASecondWorkbenchWatchesTelemetry(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, START, new String[0], "")) {
            EntityBareJid robotBare = JidCreate.entityBareFrom(RobotRig.ROBOT + "@" + PrivateXmppServer.DOMAIN);
            // the same operator at a second workbench (its own resource and connection)
            XMPPTCPConnection second = xmpp.connect(xmpp.configuration(RobotRig.OPERATOR, PrivateXmppServer.DOMAIN,
                    PrivateXmppServer.DEFAULT_PASSWORD).setResource("workbench-2").build());
            PresenceWatch.subscribe(second, robotBare); // telemetry goes to presence subscribers
            ControlMlManager watcher = ControlMlManager.getInstanceFor(second);
            AtomicInteger poses = new AtomicInteger();
            CountDownLatch tenPoses = new CountDownLatch(10);
            watcher.telemetry().addListener(Resources.POSITION, (device, pose) -> {
                poses.incrementAndGet();
                tenPoses.countDown();
            });
            // a watching workbench leases the position at the robot's full rate (unwatched: its base rate, 0.2 Hz),
            // and subscribes once the node exists (section 6's recipe: item-not-found until the first publication)
            TelemetryWatcher lease = watcher.telemetry().watcher(30);
            lease.watch(rig.robot, Map.of(Resources.POSITION, 10.0));
            long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(10);
            Outcome<Void> follow = watcher.telemetry().follow(robotBare, Resources.POSITION);
            while (!follow.isSuccess() && follow.errorOrNull().condition() == StanzaError.Condition.item_not_found
                    && System.nanoTime() < deadline) {
                follow = watcher.telemetry().follow(robotBare, Resources.POSITION);
            }
            assertTrue(follow.isSuccess(), String.valueOf(follow.errorOrNull()));

            byte[] content = new byte[70_000];
            new Random(13).nextBytes(content);
            int chunk = 32 * 1024;
            for (int offset = 0; offset < content.length; offset += chunk) {
                byte[] data = Arrays.copyOfRange(content, offset, Math.min(content.length, offset + chunk));
                Outcome<FileChunk> o = rig.operator.set(rig.robot, Resources.FS_WRITE, new FileChunk("maps/copy.bin",
                        offset, data, FileChunk.sha256Hex(data), offset + data.length == content.length));
                assertTrue(o.isSuccess(), String.valueOf(o.errorOrNull()));
            }
            assertArrayEquals(content, Files.readAllBytes(dir.resolve("fs/maps/copy.bin")), "the file on the robot");
            byte[] back = new byte[0];
            for (long offset = 0; ; ) {
                FileChunk c = rig.operator.get(rig.robot, Resources.FS_READ, new FileQuery("maps/copy.bin", offset, 0))
                        .orElseThrow();
                back = concat(back, c.data());
                offset += c.data().length;
                if (c.last()) {
                    break;
                }
            }
            assertArrayEquals(content, back, "read back through the robot");

            assertTrue(tenPoses.await(10, TimeUnit.SECONDS), "the watcher got " + poses.get() + " poses");
            lease.close();
        }
    }

    private static byte[] concat(byte[] a, byte[] b) {
        byte[] c = Arrays.copyOf(a, a.length + b.length);
        System.arraycopy(b, 0, c, a.length, b.length);
        return c;
    }
}
