package sabot.system;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Locale;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlError;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.payload.FileChunk;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MotorGains;
import sabot.controlml.payload.PidGains;
import sabot.controlml.payload.PoseEstimate;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.robot.SimProcess;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * Roles through the product (docs/CONTROLML.md section 9): one account per role, granted by the private server's
 * shared groups as a lab grants them; each does what its role allows and is refused the rest with the robot unmoved
 * and its files and gains unchanged; a revocation on the server takes effect on the running robot.
 */
class RolesTest extends RigTest {

    private static ControlMlManager account(RigTest t, String name, Role role) throws Exception {
        XMPPTCPConnection c = t.xmpp.login(name);
        if (role != Role.NONE) {
            t.xmpp.grant(c.getUser().asBareJid(), role);
        }
        ControlMlManager m = ControlMlManager.getInstanceFor(c);
        m.setRequestTimeout(Duration.ofSeconds(10));
        return m;
    }

    private static ControlMlError refused(Outcome<?> o, ControlMlCondition condition) {
        assertFalse(o.isSuccess(), "accepted");
        assertEquals(condition, o.errorOrNull().cmCondition(), o.errorOrNull().toString());
        return o.errorOrNull();
    }

    @Test
    void eachRoleDoesWhatItMayAndIsRefusedTheRestAndARevocationStopsTheNextCommand(@TempDir Path dir)
            throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, CORRIDOR_WEST, new String[0], "")) {
            ControlMlManager observer = account(this, "observer", Role.OBSERVER);
            ControlMlManager operator = account(this, "operator-2", Role.OPERATOR);
            ControlMlManager maintainer = account(this, "maintainer", Role.MAINTAINER);
            ControlMlManager stranger = account(this, "stranger", Role.NONE);
            Path files = dir.resolve("fs");
            PidGains gains = rig.get(Resources.PID);
            SimProcess.Truth before = sim(rig);
            rig.onboard.await(l -> l.contains("roles from the server's groups: maintainer: groups [sabot-maintainers]"),
                    "naming its role groups");

            // a stranger: nothing, not even a get
            refused(stranger.get(rig.robot, Resources.POSITION), ControlMlCondition.ACCESS_DENIED);
            // the observer: gets; no goal
            PoseEstimate pose = observer.get(rig.robot, Resources.POSITION).orElseThrow();
            assertEquals(before.x(), pose.pose().x(), 0.05);
            ControlMlError observerGoal = refused(observer.set(rig.robot, Resources.GOAL, goal()),
                    ControlMlCondition.SET_NOT_PERMITTED);
            assertEquals("observer@sabot.local is an observer on this device; a set of cm.goal needs the operator "
                    + "role", observerGoal.text());
            // the operator: not the gains, the files, maintenance
            ControlMlError operatorPid = refused(operator.set(rig.robot, Resources.PID, changed(gains)),
                    ControlMlCondition.SET_NOT_PERMITTED);
            assertTrue(operatorPid.text().endsWith("a set of cm.pid needs the maintainer role"), operatorPid.text());
            byte[] data = "roles".getBytes(StandardCharsets.UTF_8);
            refused(operator.set(rig.robot, Resources.FS_WRITE, new FileChunk("roles.txt", 0, data, FileChunk
                    .sha256Hex(data), true)), ControlMlCondition.SET_NOT_PERMITTED);
            ControlMlError operatorMaintenance = refused(operator.set(rig.robot, Resources.MISSION, new MissionStatus(
                    MissionState.IDLE, true, 0, "")), ControlMlCondition.SET_NOT_PERMITTED);
            assertEquals("operator-2@sabot.local is an operator on this device; switching maintenance on needs the "
                    + "maintainer role", operatorMaintenance.text());
            assertFalse(rig.get(Resources.MISSION).maintenance());
            assertEquals(gains, rig.get(Resources.PID), "the refused gains");
            assertFalse(Files.exists(files.resolve("roles.txt")), "the refused file");
            SimProcess.Truth still = sim(rig);
            assertTrue(still.distanceTo(before.x(), before.y()) < 0.01, "moved: " + before + " -> " + still);

            // the maintainer: a file, maintenance (and out of it)
            assertTrue(maintainer.set(rig.robot, Resources.FS_WRITE, new FileChunk("roles.txt", 0, data, FileChunk
                    .sha256Hex(data), true)).isSuccess());
            assertEquals("roles", Files.readString(files.resolve("roles.txt")));
            assertTrue(maintainer.set(rig.robot, Resources.MISSION, new MissionStatus(MissionState.IDLE, true, 0, ""))
                    .isSuccess());
            assertTrue(rig.get(Resources.MISSION).maintenance());
            assertTrue(maintainer.set(rig.robot, Resources.MISSION, new MissionStatus(MissionState.IDLE, false, 0, ""))
                    .isSuccess());

            // the operator's goal drives the robot
            assertTrue(operator.set(rig.robot, Resources.GOAL, goal()).isSuccess());
            awaitSpeed(rig.sim, 0.1, 15);

            // revoked on the server while it drives: from then on its commands are refused, a stop too
            long t0 = System.nanoTime();
            xmpp.revoke(xmppJid("operator-2"), Role.OPERATOR);
            Outcome<MissionStatus> probe; // "running" while it runs: changes nothing, whoever may send it
            do {
                probe = operator.set(rig.robot, Resources.MISSION, new MissionStatus(MissionState.RUNNING, false, 0,
                        ""));
                assertTrue(System.nanoTime() - t0 < TimeUnit.SECONDS.toNanos(10), "still an operator 10 s after the "
                        + "revocation: " + probe);
            } while (probe.errorOrNull() == null || probe.errorOrNull().cmCondition()
                    != ControlMlCondition.ACCESS_DENIED);
            long ms = TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - t0);
            System.out.printf(Locale.ROOT, "[figure] role revoked on the server to refused on the running robot: %d ms "
                    + "(sabot-xmpp group remove, Prosody)%n", ms);
            refused(operator.set(rig.robot, Resources.MISSION, new MissionStatus(MissionState.ABORTED, false, 0, "")),
                    ControlMlCondition.ACCESS_DENIED);
            assertEquals(MissionState.RUNNING, rig.get(Resources.MISSION).state(), "the refused stop changed nothing");
            assertTrue(maintainer.set(rig.robot, Resources.MISSION, new MissionStatus(MissionState.ABORTED, false, 0,
                    "")).isSuccess());
            awaitStandstill(rig.sim, 10);
        }
    }

    private static Goal goal() {
        return new Goal(new Pose2D(6.0, 1.0, 0), 0.1, 0.3);
    }

    private static PidGains changed(PidGains g) {
        return new PidGains(g.motors().stream().map(m -> new MotorGains(m.motor(), m.kp() + 1, m.ki(), m.kd()))
                .toList());
    }

    private static SimProcess.Truth sim(RobotRig rig) throws Exception {
        return rig.sim.truth();
    }

    private static BareJid xmppJid(String local) throws Exception {
        return JidCreate.bareFrom(local + "@" + PrivateXmppServer.DOMAIN);
    }
}
