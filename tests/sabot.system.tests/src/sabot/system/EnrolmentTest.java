package sabot.system;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.Locale;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.sasl.SASLErrorException;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.payload.Goal;
import sabot.fleet.Enrolment;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.robot.SimProcess;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * A robot's enrolment through the product (docs/SECURITY.md, "Enrolment"): started with a token in its password file,
 * it replaces the token with a password of its own (the file changes, the token no longer logs in); asking for
 * access, it obeys nobody — a maintainer of the lab is refused even a get and the robot stays where it is (the
 * simulator's truth); approved on the server, it takes the same goal and drives.
 */
class EnrolmentTest extends RigTest {

    @Test
    void aRobotStartedWithATokenObeysNobodyUntilApprovedThenDrives(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.startEnrolling(xmpp, dir, CORRIDOR_WEST)) {
            rig.onboard.await(l -> l.contains("enrolled: the enrolment token in"), "replacing its enrolment token");
            Path file = dir.resolve("xmpp-password");
            String own = Files.readAllLines(file).get(0);
            assertFalse(Enrolment.isToken(own), "the token is still in " + file);
            assertNotEquals(rig.token, own);
            assertEquals("rw-------", PosixFilePermissions.toString(Files.getPosixFilePermissions(file)));
            assertThrows(SASLErrorException.class, () -> xmpp.connect(xmpp.configuration(RobotRig.ROBOT,
                    PrivateXmppServer.DOMAIN, rig.token).setResource("check").build()), "the token logged in again");

            rig.onboard.await(l -> l.contains("accounts with a role on this robot: 0 (it obeys nobody"),
                    "saying that it obeys nobody");
            SimProcess.Truth before = rig.sim.truth();
            Goal goal = new Goal(new Pose2D(before.x() + 1.5, before.y(), 0), 0.1, 0.3);
            refused(rig.operator.set(rig.robot, Resources.GOAL, goal));
            refused(rig.operator.get(rig.robot, Resources.POSITION));
            SimProcess.Truth later = awaitSimTime(rig.sim, 1.0);
            assertEquals(before.x(), later.x(), 0.01, "a robot asking for access moved");

            long t0 = System.nanoTime();
            xmpp.approve(JidCreate.bareFrom(RobotRig.ROBOT + "@" + PrivateXmppServer.DOMAIN));
            rig.onboard.await(l -> l.contains("accounts with a role on this robot: 1 (maintainer 1)"),
                    "counting the lab's maintainer once approved");
            System.out.printf(Locale.ROOT, "[figure] approval (sabot-xmpp enrol approve) to the maintainer's role on "
                    + "the running product: %d ms%n", TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - t0));
            assertTrue(rig.operator.set(rig.robot, Resources.GOAL, goal).isSuccess(), rig.onboard.output());
            awaitTruth(rig.sim, t -> t.x() > before.x() + 0.5, 20, "driving to its goal once approved");
        }
    }

    private static void refused(Outcome<?> o) {
        assertFalse(o.isSuccess(), "a robot asking for access answered");
        assertEquals(ControlMlCondition.ACCESS_DENIED, o.errorOrNull().cmCondition(), o.errorOrNull().toString());
    }
}
