package sabot.system;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;
import java.time.Instant;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.packet.Presence;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlType;
import sabot.controlml.Outcome;
import sabot.controlml.RequestIdGenerator;
import sabot.controlml.Resources;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.LimitsPayload;
import sabot.controlml.payload.VelocityCommand;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.testsupport.robot.SimProcess;

/**
 * The robot stops by itself, proven on the simulator's ground truth: joystick silence (deadman), a motor board that
 * stops answering, and a noisy bus that must not stop it.
 */
class SafetyTest extends RigTest {

    static final double[] START = CORRIDOR_MIDDLE;
    static final double SPEED = 0.3;
    static final double DEADMAN = 0.5;

    @Test
    void robotStopsWhenJoystickGoesSilent(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, START, new String[0], "")) {
            for (int i = 0; i < 3 * JOYSTICK_HZ; i++) {
                assertTrue(rig.operator.set(rig.robot, Resources.VELOCITY, new VelocityCommand(Instant.now(),
                        new Twist2D(SPEED, 0))).isSuccess(), rig.onboard.output());
                TimeUnit.MILLISECONDS.sleep(1000 / JOYSTICK_HZ); // the stimulus: a joystick at 10 Hz
            }
            SimProcess.Truth atSilence = rig.sim.truth();
            assertTrue(atSilence.v() > 0.8 * SPEED, "not driving at the joystick's speed: " + atSilence);

            double bound = DEADMAN + atSilence.v() / A_MAX + 0.25;
            SimProcess.Truth stopped = awaitStandstill(rig.sim, bound + 2);
            double stopTime = stopped.t() - atSilence.t();
            double travelled = stopped.distanceTo(atSilence.x(), atSilence.y());
            double brakingDistance = atSilence.v() * DEADMAN + atSilence.v() * atSilence.v() / (2 * A_MAX);
            assertTrue(stopTime <= bound, "stopped " + stopTime + " s after the last twist, bound " + bound + " s");
            assertTrue(travelled <= brakingDistance + 0.05, "travelled " + travelled + " m after the last twist, "
                    + "bound " + brakingDistance + " m");
            rig.onboard.await(l -> l.contains("deadman"), "reporting the deadman stop");
        }
    }

    /**
     * Commands that arrive late do not move the robot: a twist sent 2 s ago (older than {@code teleop.maxAge},
     * 0.5 s) and a goal sent 10 s ago (older than {@code controlml.staleCommandAfter}, 5 s) are refused as
     * {@code stale-command} by their send time, and the robot stands still.
     */
    @Test
    void aTwistOrAGoalSentTooLongAgoIsRefusedAndTheRobotStandsStill(@TempDir Path dir) throws Exception {
        RequestIdGenerator ids = new RequestIdGenerator(); // this test's own requests, sent as they are
        try (RobotRig rig = RobotRig.start(xmpp, dir, START, new String[0], "")) {
            SimProcess.Truth before = rig.sim.truth();
            for (int i = 0; i < JOYSTICK_HZ; i++) {
                Instant sent = Instant.now().minusSeconds(2);
                Outcome<ControlMlElement> twist = rig.operator.exchange(rig.robot, ControlMlElement.request(
                        ControlMlType.SET, ids.next(), "cm.velocity", Resources.VELOCITY.codec()
                                .encode(new VelocityCommand(sent, new Twist2D(SPEED, 0)))).withSent(sent));
                assertEquals(ControlMlCondition.STALE_COMMAND, twist.errorOrNull().cmCondition(), twist::toString);
                assertTrue(twist.errorOrNull().text().contains("teleop.maxAge"), twist.errorOrNull().text());
                TimeUnit.MILLISECONDS.sleep(1000 / JOYSTICK_HZ); // the stimulus: a joystick at 10 Hz
            }
            Outcome<ControlMlElement> goal = rig.operator.exchange(rig.robot, ControlMlElement.request(ControlMlType
                    .SET, ids.next(), "cm.goal", Resources.GOAL.codec().encode(new Goal(
                            new Pose2D(START[0] + 2, START[1], 0), 0.15, 0.3))).withSent(Instant.now().minusSeconds(
                                    10)));
            assertEquals(ControlMlCondition.STALE_COMMAND, goal.errorOrNull().cmCondition(), goal::toString);
            SimProcess.Truth later = awaitSimTime(rig.sim, 3);
            assertTrue(later.distanceTo(before.x(), before.y()) < 0.01, "moved on a stale command: " + later);
            assertEquals(MissionState.IDLE, rig.get(Resources.MISSION).state());
        }
    }

    @Test
    void robotBrakesAndReportsWhenTheMotorBoardStopsAnswering(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, START, new String[0], "")) {
            PresenceWatch presence = PresenceWatch.subscribe(rig.operatorConnection, rig.robot.asBareJid());
            SimProcess.Truth moving = sendEastAndAwaitSpeed(rig);
            presence.await(p -> p.getMode() == Presence.Mode.dnd, "busy while driving");
            rig.sim.command("board 1 sact off");
            SimProcess.Truth stopped = awaitStandstill(rig.sim, 5);
            // the board's own deadman (0.3 s) and the deceleration bound the stop
            assertTrue(stopped.t() - moving.t() < 0.3 + 0.5 + moving.v() / A_MAX + 0.5, "stopped after "
                    + (stopped.t() - moving.t()) + " s");
            rig.onboard.await(l -> l.contains("fault: the sact board does not answer"), "reporting the fault");
            MissionStatus failed = rig.get(Resources.MISSION);
            assertEquals(MissionState.FAILED, failed.state(), failed.toString());
            assertTrue(failed.detail().contains("sact"), failed.toString());
            presence.await(p -> p.getMode() == Presence.Mode.away && String.valueOf(p.getStatus()).contains("sact"),
                    "away, naming the board");

            rig.sim.command("board 1 sact on");
            SimProcess.Truth later = awaitSimTime(rig.sim, 1.5);
            assertTrue(later.distanceTo(stopped.x(), stopped.y()) < 0.01, "moved again without a command: " + later);
        }
    }

    @Test
    void aJammedWheelIsAMotorFaultThatStopsTheRobotUntilANewCommand(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, START, new String[0], "")) {
            PresenceWatch presence = PresenceWatch.subscribe(rig.operatorConnection, rig.robot.asBareJid());
            SimProcess.Truth moving = sendEastAndAwaitSpeed(rig);
            rig.sim.command("wheel 1 left jam");
            SimProcess.Truth stopped = awaitStandstill(rig.sim, 5);
            // the firmware latches a following error within a fraction of a second; the loop sees it at its next
            // write (a refused set-point) and brakes the other motor too
            assertTrue(stopped.t() - moving.t() < 1.5, "stopped " + (stopped.t() - moving.t()) + " s after the jam");
            rig.onboard.await(l -> l.contains("fault: left motor fault: following error"), "reporting the motor fault");
            MissionStatus failed = rig.get(Resources.MISSION);
            assertEquals(MissionState.FAILED, failed.state(), failed.toString());
            assertTrue(failed.detail().contains("left motor fault"), failed.toString());
            presence.await(p -> p.getMode() == Presence.Mode.away
                    && String.valueOf(p.getStatus()).contains("left motor fault"), "away, naming the motor");

            rig.sim.command("wheel 1 left free");
            SimProcess.Truth later = awaitSimTime(rig.sim, 1.5);
            assertTrue(later.distanceTo(stopped.x(), stopped.y()) < 0.01, "moved again without a command: " + later);
            sendEastAndAwaitSpeed(rig); // a new goal acknowledges the fault and drives again
        }
    }

    /** Sends the robot east along the corridor (8.0, 1.0) and waits until its true speed passes 0.2 m/s. */
    private static SimProcess.Truth sendEastAndAwaitSpeed(RobotRig rig) throws Exception {
        assertTrue(rig.operator.set(rig.robot, Resources.GOAL, new Goal(new Pose2D(8.0, 1.0, 0), 0.1, 0.3))
                .isSuccess(), rig.onboard.output());
        return awaitSpeed(rig.sim, 0.2, 20);
    }

    @Test
    void goalIsReachedOnANoisyBus(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, START, new String[] { "--fault-crc", "0.02", "--fault-drop",
                "0.02" }, "")) {
            Pose2D goal = new Pose2D(6.5, 1.5, 0);
            assertTrue(rig.operator.set(rig.robot, Resources.GOAL, new Goal(goal, 0.15, 0.3)).isSuccess(),
                    rig.onboard.output());
            rig.onboard.await(l -> l.contains("goal reached"), "saying the goal is reached", 90);
            SimProcess.Truth truth = rig.sim.truth();
            System.out.printf("[noisy bus] truth %s, %.3f m from the goal; estimate %s%n", truth, truth.distanceTo(
                    goal.x(), goal.y()), rig.get(Resources.POSITION).pose());
            assertTrue(truth.distanceTo(goal.x(), goal.y()) <= 0.15, truth.toString());
            assertEquals(0, truth.contacts());
        }
    }

    @Test
    void robotBrakesWhenItsEstimateBecomesTooUncertain(@TempDir Path dir) throws Exception {
        // 3 cm: odometry's uncertainty passes it after a few metres of driving
        try (RobotRig rig = RobotRig.start(xmpp, dir, START, new String[0], "localizer.maxPositionSigma = 0.03\n")) {
            assertTrue(rig.operator.set(rig.robot, Resources.GOAL, new Goal(new Pose2D(9.5, 1.0, 0), 0.1, 0.3))
                    .isSuccess(), rig.onboard.output());
            rig.onboard.await(l -> l.contains("fault: position uncertainty"), "reporting the uncertain estimate", 60);
            SimProcess.Truth stopped = awaitStandstill(rig.sim, 5);
            MissionStatus failed = rig.get(Resources.MISSION);
            assertEquals(MissionState.FAILED, failed.state(), failed.toString());
            assertTrue(failed.detail().contains("uncertainty"), failed.toString());
            SimProcess.Truth later = awaitSimTime(rig.sim, 1.0);
            assertTrue(later.distanceTo(stopped.x(), stopped.y()) < 0.01, "moved again: " + later);
        }
    }

    @Test
    void robotBrakesWhenTheProductIsStopped(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, START, new String[0], "")) {
            assertTrue(rig.operator.set(rig.robot, Resources.GOAL, new Goal(new Pose2D(9.5, 1.0, 0), 0.1, 0.3))
                    .isSuccess(), rig.onboard.output());
            SimProcess.Truth moving = awaitSpeed(rig.sim, 0.3, 20);
            assertEquals(0, rig.onboard.stop(), rig.onboard.output());
            SimProcess.Truth stopped = awaitStandstill(rig.sim, 5);
            assertTrue(stopped.t() - moving.t() < 1.0 + moving.v() / A_MAX, "stopped after " + (stopped.t()
                    - moving.t()) + " s");
            assertTrue(rig.onboard.output().contains("motion task stopped, robot braked"), rig.onboard.output());
        }
    }

    @Test
    void limitsSetOverControlMlAreEnforcedOnTheRobot(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, START, new String[0], "")) {
            double slow = 0.2;
            assertTrue(rig.operator.set(rig.robot, Resources.LIMITS, new LimitsPayload(slow, 1.0, 0.5, 2.5))
                    .isSuccess(), rig.onboard.output());
            assertEquals(slow, rig.get(Resources.LIMITS).maxLinearSpeed(), 1e-9);
            assertTrue(rig.operator.set(rig.robot, Resources.GOAL, new Goal(new Pose2D(7.5, 1.0, 0), 0.15, 0.3))
                    .isSuccess(), rig.onboard.output());
            // a metre at the limit (reached within 4 cm at 0.5 m/s²), the truth read every 20 ms
            double[] fastest = { 0 };
            double past = START[0] + 1.0;
            awaitTruth(rig.sim, t -> {
                fastest[0] = Math.max(fastest[0], Math.abs(t.v()));
                return t.x() > past;
            }, 40, "past x = " + past + " m");
            assertTrue(fastest[0] <= slow * 1.05, "drove at " + fastest[0] + " m/s with a limit of " + slow);
            assertTrue(fastest[0] >= slow * 0.7, "barely moved: " + fastest[0] + " m/s");

            assertFalse(rig.operator.set(rig.robot, Resources.LIMITS, new LimitsPayload(5.0, 1.0, 0.5, 2.5))
                    .isSuccess(), "a limit above the robot's physical one was accepted");
            assertEquals(slow, rig.get(Resources.LIMITS).maxLinearSpeed(), 1e-9, "a refused set changed the limits");
        }
    }
}
