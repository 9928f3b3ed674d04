package sabot.system;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;

import java.nio.file.Path;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.roster.AbstractRosterListener;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.jxmpp.jid.EntityBareJid;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlManager;
import sabot.controlml.ControlMlType;
import sabot.controlml.PendingCommand;
import sabot.controlml.Resources;
import sabot.controlml.payload.Goal;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.robot.OnboardProcess;
import sabot.testsupport.robot.SimProcess;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * Commands for a robot that is down (docs/CONTROLML.md section 5, "Commands for an offline device"), through the
 * product: a goal sent as a stored message while the robot's product is stopped waits at the server, across a restart
 * of the server, and is driven when the robot comes back within its stale limit; the same command is refused as
 * stale by a robot that comes back after it, which stays where it is. The answers reach the operator, who was away
 * meanwhile, from the server's offline store.
 */
class OfflineCommandTest extends RigTest {

    private static final long TIMEOUT_S = 30;

    @Test
    void aGoalSentWhileTheRobotIsDownIsDrivenWhenItComesBackAcrossAServerRestart(@TempDir Path dir)
            throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, CORRIDOR_WEST, new String[0], "controlml.staleCommandAfter = 120\n")) {
            SimProcess.Truth before = rig.sim.truth();
            PendingCommand<Goal> sent = sendWhileDown(rig, new Goal(new Pose2D(before.x() + 1.0, before.y(), 0), 0.1,
                    0.3));
            // the server restarts with the command in its offline store
            xmpp.stopServer();
            xmpp.restart();
            BlockingQueue<ControlMlElement> answers = operatorAgain();
            try (OnboardProcess again = OnboardProcess.start(rig.onboard.config())) {
                again.await(l -> l.contains("XMPP session online"), "saying the XMPP session is online again");
                awaitTruth(rig.sim, t -> t.x() > before.x() + 0.3, 30, "driving to the goal sent while it was down");
                ControlMlElement answer = answers.poll(TIMEOUT_S, TimeUnit.SECONDS);
                assertNotNull(answer, "no answer reached the operator");
                assertEquals(sent.id(), answer.id());
                assertEquals(ControlMlType.RESULT, answer.type(), answer.toString());
            }
        }
    }

    @Test
    void aGoalOlderThanTheStaleLimitIsRefusedAndTheRobotStaysWhereItIs(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, CORRIDOR_WEST, new String[0], "controlml.staleCommandAfter = 1\n")) {
            SimProcess.Truth before = rig.sim.truth();
            PendingCommand<Goal> sent = sendWhileDown(rig, new Goal(new Pose2D(before.x() + 1.0, before.y(), 0), 0.1,
                    0.3));
            BlockingQueue<ControlMlElement> answers = operatorAgain();
            // the product takes seconds to start: the command is older than 1 s when it arrives
            try (OnboardProcess again = OnboardProcess.start(rig.onboard.config())) {
                again.await(l -> l.contains("XMPP session online"), "saying the XMPP session is online again");
                ControlMlElement answer = answers.poll(TIMEOUT_S, TimeUnit.SECONDS);
                assertNotNull(answer, "no answer reached the operator");
                assertEquals(sent.id(), answer.id());
                assertEquals(ControlMlType.ERROR, answer.type(), answer.toString());
                assertEquals(ControlMlCondition.STALE_COMMAND, answer.failure().cmCondition(), answer.toString());
                SimProcess.Truth later = awaitSimTime(rig.sim, 2.0);
                assertEquals(before.x(), later.x(), 0.01, "a stale goal moved the robot");
            }
        }
    }

    /**
     * Stops the robot's product, waits until the operator sees it unavailable (the server has no session of it left,
     * so the message is stored, not delivered to a dying session) and sends the goal as a stored message; the
     * operator then goes away too.
     */
    private static PendingCommand<Goal> sendWhileDown(RobotRig rig, Goal goal) throws Exception {
        Roster roster = Roster.getInstanceFor(rig.operatorConnection);
        EntityBareJid robot = rig.robot.asEntityBareJidIfPossible();
        CountDownLatch gone = new CountDownLatch(1);
        roster.addRosterListener(new AbstractRosterListener() {
            @Override
            public void presenceChanged(Presence presence) {
                if (presence.getFrom().asBareJid().equals(robot) && !roster.getPresence(robot).isAvailable()) {
                    gone.countDown();
                }
            }
        });
        rig.onboard.close();
        if (roster.getPresence(robot).isAvailable()) {
            assertEquals(true, gone.await(TIMEOUT_S, TimeUnit.SECONDS), "the robot's presence never went");
        }
        PendingCommand<Goal> sent = rig.operator.sendCommandMessage(robot, Resources.GOAL, goal);
        rig.operatorConnection.disconnect(); // the operator goes away: the answer waits for it at the server
        return sent;
    }

    /** The operator back on another connection: the answers it finds come to it unsolicited. */
    private BlockingQueue<ControlMlElement> operatorAgain() throws Exception {
        BlockingQueue<ControlMlElement> answers = new LinkedBlockingQueue<>();
        XMPPTCPConnection c = new XMPPTCPConnection(xmpp.configuration(RobotRig.OPERATOR, PrivateXmppServer.DOMAIN,
                PrivateXmppServer.DEFAULT_PASSWORD).setResource("again").build());
        ControlMlManager.getInstanceFor(c).addUnsolicitedAnswerListener((from, element) -> answers.offer(element));
        xmpp.connect(c);
        return answers;
    }
}
