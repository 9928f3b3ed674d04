package sabot.fleet.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Duration;
import java.util.Locale;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

import org.jivesoftware.smack.packet.StanzaError.Condition;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.Tag;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;

import sabot.controlml.AccessPolicy;
import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.PendingCommand;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.StaleCommandPolicy;
import sabot.controlml.payload.Goal;
import sabot.fleet.AccessRules;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * A partition between the two domains of a federation (docs/FEDERATION.md): the s2s link goes dead (nothing passes,
 * nothing is closed, as behind a broken switch). A command sent as a stored message (docs/CONTROLML.md section 5,
 * "Commands for an offline device") is held on the way; when the link heals it arrives, and the robot judges it by
 * its stale-command policy: applied when younger than the robot's limit, refused {@code stale-command} when older.
 */
@Tag("ejabberd")
class FederationPartitionTest {

    static final long TIMEOUT_S = 10;
    /** How long the link stays dead: what the commands age on the way. */
    static final Duration PARTITION = Duration.ofSeconds(1);

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.federationThroughRelays();

    private static final String PASSWORD = "partition-pw";

    private static XMPPTCPConnection on(String localpart, String domain) throws Exception {
        XMPP.register(localpart, domain, PASSWORD);
        return XMPP.connect(XMPP.configuration(localpart, domain, PASSWORD).build());
    }

    /** A robot of sabot2.local serving cm.goal under the lab's groups and {@code stale}; @return its goal */
    private static Goal[] robot(XMPPTCPConnection robot, XMPPTCPConnection operator, StaleCommandPolicy stale)
            throws Exception {
        AccessPolicy policy = AccessRules.labGroups().on(robot);
        Goal[] goal = FleetOnServerTest.goalDevice(robot, policy);
        ControlMlManager.getInstanceFor(robot).setStaleCommandPolicy(stale);
        XMPP.enrolRobot(robot.getUser().asBareJid());
        FleetOnServerTest.awaitRole(Roster.getInstanceFor(robot), policy, operator, Role.OPERATOR);
        return goal;
    }

    @Test
    void commandsHeldByAPartitionArriveWhenItHealsAndTheRobotJudgesTheirAge() throws Exception {
        XMPPTCPConnection operator = on("p-operator", PrivateXmppServer.DOMAIN);
        XMPPTCPConnection fresh = on("p-robot-fresh", PrivateXmppServer.SECOND_DOMAIN);
        XMPPTCPConnection strict = on("p-robot-strict", PrivateXmppServer.SECOND_DOMAIN);
        XMPP.grantOn(PrivateXmppServer.SECOND_DOMAIN, operator.getUser().asBareJid(), Role.OPERATOR);
        Goal[] freshGoal = robot(fresh, operator, StaleCommandPolicy.DEFAULT); // refuses sets older than 5 s
        Goal[] strictGoal = robot(strict, operator, StaleCommandPolicy.refuseOlderThan(Duration.ofMillis(500)));
        ControlMlManager cm = ControlMlManager.getInstanceFor(operator);
        // the s2s connections up both ways before the partition (a request there, its answer back)
        for (XMPPTCPConnection r : new XMPPTCPConnection[] { fresh, strict }) {
            assertTrue(cm.get(r.getUser(), Resources.GOAL).isSuccess(), "no link before the partition");
        }

        XMPP.partition();
        Goal target = new Goal(new Pose2D(5, 1, 0), 0.1, 0.1);
        PendingCommand<Goal> toFresh = cm.sendCommandMessage(fresh.getUser().asEntityBareJid(), Resources.GOAL,
                target);
        PendingCommand<Goal> toStrict = cm.sendCommandMessage(strict.getUser().asEntityBareJid(), Resources.GOAL,
                target);
        // held while the link is dead: no answer within the partition (its length is what the commands age)
        assertThrows(TimeoutException.class, () -> toFresh.outcome().get(PARTITION.toMillis(),
                TimeUnit.MILLISECONDS), "a command crossed the partition");
        assertEquals(Pose2D.ORIGIN, freshGoal[0].pose(), "a command crossed the partition");
        assertEquals(Pose2D.ORIGIN, strictGoal[0].pose(), "a command crossed the partition");

        long healed = System.nanoTime();
        XMPP.heal();
        Outcome<Goal> applied = toFresh.outcome().get(TIMEOUT_S, TimeUnit.SECONDS);
        long answered = System.nanoTime();
        Outcome<Goal> refused = toStrict.outcome().get(TIMEOUT_S, TimeUnit.SECONDS);
        assertTrue(applied.isSuccess(), applied::toString);
        assertEquals(target, freshGoal[0], "the command younger than the robot's limit");
        assertEquals(ControlMlCondition.STALE_COMMAND, refused.errorOrNull().cmCondition(), refused::toString);
        assertEquals(Condition.not_acceptable, refused.errorOrNull().condition());
        assertEquals(Pose2D.ORIGIN, strictGoal[0].pose(), "the command older than the robot's limit was applied");
        System.out.printf(Locale.ROOT, "[figure] federation: a %d ms partition healed to the held command's answer: "
                + "%d ms; refused by the 500 ms robot: %s%n", PARTITION.toMillis(), TimeUnit.NANOSECONDS.toMillis(
                        answered - healed), refused.errorOrNull().text());
    }
}
