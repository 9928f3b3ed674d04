package sabot.onboard.motion.loop;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.util.List;

import org.junit.jupiter.api.Test;

import sabot.control.MotionLimits;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.TrajectoryPoint;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.robot.BatteryState;
import sabot.onboard.motion.loop.ControlLoop.Mode;
import sabot.onboard.motion.loop.FakeBoards.WheelWrite;
import sabot.onboard.motion.loop.LoopHost.PlanRequest;

/**
 * The robot's control loop ticked period by period on fake boards and a fake clock, as ros2_control's
 * test_diff_drive_controller drives its controller: each test asserts what the wheels received. Each runs in
 * milliseconds of real time.
 */
class ControlLoopTest {

    private static final double PERIOD = 0.02;
    private static final double R = LoopRig.ROBOT.wheelRadius();

    private final LoopRig rig = new LoopRig();

    @Test
    void robotHaltsWhenJoystickGoesSilent() {
        rig.run(0.1);
        rig.joystick(0.3, 0);
        rig.run(0.3);
        assertTrue(rig.boards.lastWrite().left() * R > 0.1, "driving by joystick: " + rig.boards.lastWrite());
        rig.run(LoopRig.DEADMAN - 0.3 - PERIOD);
        assertFalse(rig.boards.braked(), "the twist is still fresh one period before the deadman");
        ControlLoop.Snapshot s = rig.run(2 * PERIOD);
        assertTrue(rig.boards.braked(), "braked once the twist is older than the deadman");
        assertEquals(Mode.IDLE, s.mode());
        assertEquals(new WheelWrite(rig.boards.lastWrite().time(), 0, 0), rig.boards.lastWrite());
    }

    @Test
    void joystickDeadmanIsJudgedOnTheTwistsReceiveTime() {
        rig.run(0.1);
        // received 0.6 s ago (a late command queue): too old to drive on
        rig.loop.teleop(new Twist2D(0.3, 0), rig.clock.nanoTime() - 600_000_000L,
                rig.clock.now());
        ControlLoop.Snapshot s = rig.tick();
        assertTrue(rig.boards.braked(), "braked in the period that took the twist");
        assertEquals(Mode.IDLE, s.mode());
        rig.tick();
        assertEquals(0, rig.boards.lastWrite().left(), 0.0);
    }

    @Test
    void motorFaultBrakesAndStaysLatchedUntilANewCommand() {
        rig.run(0.1);
        rig.joystick(0.3, 0);
        rig.run(0.2);
        rig.boards.motorFault = true;
        rig.joystick(0.3, 0);
        ControlLoop.Snapshot s = rig.tick();
        assertEquals(Mode.FAULT, s.mode());
        assertTrue(rig.boards.braked());
        assertEquals(MissionState.FAILED, s.mission().state());
        assertTrue(s.mission().detail().contains("following error"), s.mission().detail());
        int writes = rig.boards.writes.size();
        s = rig.run(1.0);
        assertEquals(Mode.FAULT, s.mode(), "the fault stays latched");
        assertEquals(writes, rig.boards.writes.size(), "no set-point while faulted");
        assertTrue(rig.boards.braked());
        rig.joystick(0.2, 0);
        s = rig.run(0.1);
        assertEquals(Mode.TELEOP, s.mode(), "a new command releases the brake");
        assertFalse(rig.boards.braked());
        assertTrue(rig.boards.writes.size() > writes);
    }

    @Test
    void wheelSetPointsNeverExceedTheLimitsAndAccelerateWithinThem() {
        MotionLimits lower = new MotionLimits(0.3, 0.4, 1.0, 0.3, LoopRig.LIMITS.maxWheelRimSpeed(),
                LoopRig.LIMITS.trackWidth());
        rig.loop.limitsChanged(lower);
        rig.run(0.1);
        int first = rig.boards.writes.size();
        // full forward with a hard turn, then full reverse the other way: far beyond the limits
        for (int i = 0; i < 10; i++) {
            rig.joystick(2.0, 5.0);
            rig.run(0.1);
        }
        for (int i = 0; i < 10; i++) {
            rig.joystick(-2.0, -5.0);
            rig.run(0.1);
        }
        List<WheelWrite> w = rig.boards.writes.subList(first, rig.boards.writes.size());
        double half = lower.trackWidth() / 2;
        double fastest = 0;
        for (int i = 0; i < w.size(); i++) {
            double l = w.get(i).left() * R;
            double r = w.get(i).right() * R;
            double v = (l + r) / 2;
            double omega = (r - l) / (2 * half);
            fastest = Math.max(fastest, Math.abs(v));
            assertTrue(Math.abs(v) <= lower.maxLinearSpeed() + 1e-9, "v " + v + " at " + w.get(i));
            assertTrue(Math.abs(omega) <= lower.maxAngularSpeed() + 1e-9, "omega " + omega + " at " + w.get(i));
            if (i > 0) {
                double dt = w.get(i).time() - w.get(i - 1).time();
                double step = lower.maxLinearAcceleration() * dt + 1e-9;
                assertTrue(Math.abs(l - w.get(i - 1).left() * R) <= step, "left wheel jumps at " + w.get(i));
                assertTrue(Math.abs(r - w.get(i - 1).right() * R) <= step, "right wheel jumps at " + w.get(i));
            }
        }
        // the outer wheel (v + omega d/2 = 0.45 m/s) needs 1.1 s at 0.4 m/s2 to reach the speed limit's twist
        assertTrue(fastest > 0.8 * lower.maxLinearSpeed(), "the joystick drove near the limit: " + fastest);
    }

    @Test
    void missionIsDoneOnlyAtTheGoalAndAtRest() {
        rig.run(0.1);
        // facing the other way than the trajectory arrives: the robot turns in place at the goal
        rig.navigateTo(4, 5, Math.PI / 2);
        ControlLoop.Snapshot s = rig.tick();
        assertEquals(MissionState.RUNNING, s.mission().state());
        for (int i = 0; i < 30 * 50 && s.mission().state() == MissionState.RUNNING; i++) {
            s = rig.tick();
        }
        assertEquals(MissionState.DONE, s.mission().state(), s.mission().detail());
        Pose2D at = s.pose().pose();
        assertTrue(Math.hypot(at.x() - 4, at.y() - 5) <= 0.05, "at the goal: " + at);
        assertTrue(Math.abs(Pose2D.normalizeAngle(at.theta() - Math.PI / 2)) <= 0.1, "facing the goal's way: " + at);
        assertTrue(Math.abs(s.velocity().twist().linear()) < 0.05 && Math.abs(s.velocity().twist().angular()) < 0.1,
                "at rest: " + s.velocity().twist());
        assertTrue(rig.boards.braked(), "braked at the goal");
        assertEquals(MissionState.DONE, rig.missions.get(rig.missions.size() - 1).state());
    }

    @Test
    void robotThatMakesNoProgressReplans() {
        rig.boards.stuck = true;
        rig.run(0.1);
        rig.navigateTo(8, 5, 0);
        ControlLoop.Snapshot s = rig.run(LoopRig.PROGRESS_TIME - 0.5);
        assertEquals(Mode.FOLLOW, s.mode());
        assertTrue(rig.planRequests.isEmpty(), "no replanning before the progress time");
        s = rig.run(1.0);
        assertEquals(Mode.BLOCKED, s.mode());
        assertEquals(1, rig.planRequests.size(), "one plan request to the host");
        rig.boards.stuck = false;
        rig.answerPlanRequests();
        assertNotEquals(Mode.BLOCKED, rig.tick().mode(), "a new trajectory");
    }

    @Test
    void echoOnThePathAheadStopsTheRobotAndReplansAroundIt() {
        rig.run(0.1);
        rig.navigateTo(7, 5, 0);
        ControlLoop.Snapshot s = rig.run(2.0);
        assertEquals(Mode.FOLLOW, s.mode());
        List<TrajectoryPoint> before = s.trajectory().points();
        Pose2D here = s.pose().pose();
        Point2D echo = new Point2D(here.x() + 1.0, here.y());
        // the sonar sees something 1 m ahead for a few of its reads
        rig.boards.echoes = List.of(new Point2D(1.0, 0));
        s = rig.run(0.2);
        rig.boards.echoes = List.of();
        assertEquals(Mode.BLOCKED, s.mode());
        assertEquals(1, rig.planRequests.size());
        PlanRequest request = rig.planRequests.get(0);
        assertTrue(request.obstacles().stream().anyMatch(p -> Math.hypot(p.x() - echo.x(), p.y() - echo.y()) < 0.1),
                "the echo is planned around: " + request.obstacles());
        rig.answerPlanRequests();
        s = rig.tick();
        assertNotEquals(Mode.BLOCKED, s.mode());
        List<TrajectoryPoint> after = s.trajectory().points();
        assertNotEquals(before, after);
        for (TrajectoryPoint p : after) {
            assertTrue(Math.hypot(p.x() - echo.x(), p.y() - echo.y()) >= LoopRig.ROBOT_RADIUS,
                    "the new trajectory keeps clear of the echo: " + p);
        }
    }

    // ------------------------------------------------------------------------------------------ collision guard

    /** The joystick at the top speed towards a mapped wall: the robot stops short of it, within the guard's margin. */
    @Test
    void joystickTowardsAMappedWallStopsShortOfIt() {
        LoopRig walled = new LoopRig(LoopRig.wallAt(4.0));
        walled.run(0.1);
        ControlLoop.Snapshot s = walled.drive(LoopRig.LIMITS.maxLinearSpeed(), 0, 8);
        double front = s.pose().pose().x() + LoopRig.ROBOT_RADIUS;
        double gap = 4.0 - front;
        assertTrue(gap >= 0, "touched the wall: front at " + front);
        assertTrue(gap <= LoopDefaults.GUARD_MARGIN + 0.05, "stopped " + gap + " m short: the guard over-brakes");
        assertEquals(0, walled.boards.lastWrite().left(), 1e-9, "at rest against the wall");
        assertTrue(walled.loop.guardStatus().startsWith("stopped: obstacle 0.0"), walled.loop.guardStatus());
        assertEquals(walled.loop.guardStatus(), walled.loop.snapshot().mission().detail(), "the operator reads why");
        // turning in place stays allowed there
        walled.drive(0, 1.0, 0.5);
        assertTrue(walled.boards.lastWrite().left() < 0 && walled.boards.lastWrite().right() > 0,
                "turns in place: " + walled.boards.lastWrite());
    }

    /** Far from the wall the guard leaves the joystick's speed alone. */
    @Test
    void joystickInOpenSpaceKeepsTheCommandedSpeed() {
        LoopRig walled = new LoopRig(LoopRig.wallAt(4.0));
        walled.run(0.1);
        walled.drive(0.3, 0, 1.5);
        assertEquals(0.3, walled.boards.lastWrite().left() * R, 1e-9, "full speed 1.5 m from the wall");
        assertEquals("", walled.loop.guardStatus());
    }

    /** An echo ahead — no wall on the map — stops the joystick as well: the sonar is read while a joystick drives. */
    @Test
    void joystickTowardsAnEchoStopsShortOfIt() {
        Point2D post = new Point2D(2.9, 5.0);
        ControlLoop.Snapshot s = rig.run(0.1);
        for (double t = 0; t < 6; t += 0.1) {
            // the post comes into the sonar's view only once the joystick drives; it sees it where it stands
            Pose2D p = s.pose().pose();
            double dx = post.x() - p.x();
            double dy = post.y() - p.y();
            rig.boards.echoes = t < 0.5 ? List.of() : List.of(new Point2D(dx * Math.cos(p.theta()) + dy * Math.sin(
                    p.theta()), -dx * Math.sin(p.theta()) + dy * Math.cos(p.theta())));
            rig.joystick(0.4, 0);
            s = rig.run(0.1);
        }
        double gap = post.x() - (s.pose().pose().x() + LoopRig.ROBOT_RADIUS);
        assertTrue(gap >= 0 && gap <= LoopDefaults.GUARD_MARGIN + 0.05, "gap to the echo " + gap + " m");
        assertEquals(0, rig.boards.lastWrite().left(), 1e-9);
        assertTrue(rig.loop.guardStatus().startsWith("stopped: obstacle"), rig.loop.guardStatus());
    }

    /** Backwards, where no sensor looks, the joystick is held to the creep speed even in open space. */
    @Test
    void reversingIsHeldToTheCreepSpeed() {
        rig.run(0.1);
        rig.drive(-0.3, 0, 1.0);
        assertEquals(-LoopDefaults.REVERSE_SPEED, rig.boards.lastWrite().left() * R, 1e-9);
        assertTrue(rig.loop.guardStatus().startsWith("reversing at 0.10 m/s"), rig.loop.guardStatus());
    }

    /**
     * The PID step test's move runs on the motor board, beyond the guard: the loop judges it before it starts. The
     * robot stands 3 cm from a wall facing it; a step of either wheel forwards would turn its front into the wall.
     */
    @Test
    void aStepTestTowardsAWallIsRefusedAndOneAwayFromItIsNot() {
        LoopRig walled = new LoopRig(LoopRig.wallAt(4.0));
        walled.run(0.1);
        walled.loop.relocalise(new Pose2D(4.0 - LoopRig.ROBOT_RADIUS - 0.03, 5.0, 0));
        walled.run(0.1);
        String left = walled.loop.stepTestBlocked(0, 0.004);
        assertTrue(left != null && left.startsWith("collision guard: the step turns the robot about its right wheel")
                && left.contains("motion.guardMargin"), left);
        assertTrue(walled.loop.stepTestBlocked(1, 0.004).contains("about its left wheel"));
        assertNull(walled.loop.stepTestBlocked(0, -0.004), "stepping back, away from the wall");
        assertNull(walled.loop.stepTestBlocked(1, -0.004), "stepping back, away from the wall");
        assertNull(walled.loop.stepTestBlocked(2, 0.004), "an unknown motor is the board's to refuse");
        rig.run(0.1);
        assertNull(rig.loop.stepTestBlocked(0, 0.004), "in the open");
    }

    /** The power board is read about once a second, in spare slots the other boards do not need. */
    @Test
    void theBatteryIsReadAboutOnceASecondAndStampedWithTheLoopsClock() {
        rig.run(10.0);
        ControlLoop.Snapshot s = rig.tick();
        // 500 periods, 250 spare slots, one in 24 to the power board
        assertEquals(250 / SensorRounds.BATTERY_SLOTS, rig.boards.batteryReads, 1);
        BatteryState b = s.battery().orElseThrow();
        assertEquals(0.8, b.stateOfCharge(), 0.0);
        assertTrue(!b.measured().isAfter(rig.clock.now()) && !b.measured().isBefore(rig.clock.now().minusSeconds(2)),
                b.measured() + " at " + rig.clock.now());
        assertEquals("", s.batteryFault());
        rig.boards.batteryCharge = 0.3;
        rig.run(2.0);
        assertEquals(0.3, rig.tick().battery().orElseThrow().stateOfCharge(), 0.0);
    }

    /**
     * A power board that fails (silent, or a reading no battery gives) is a fault the snapshot names, the last good
     * reading kept with its stamp; the loop drives on, asks again only every few seconds, and clears the fault once a
     * reading is good.
     */
    @Test
    void aFailingPowerBoardIsAFaultWithItsReasonAndTheLoopDrivesOn() {
        rig.run(2.0);
        BatteryState good = rig.tick().battery().orElseThrow();
        rig.boards.batteryFailure = new IOException("power: state_of_charge 12000 is outside the register map's "
                + "bounds [0, 10000]");
        rig.joystick(0.3, 0);
        ControlLoop.Snapshot s = rig.tick();
        for (int i = 0; i < 100 && s.batteryFault().isEmpty(); i++) { // the next battery slot, within 2 s
            rig.joystick(0.3, 0);
            s = rig.tick();
        }
        assertEquals("power: state_of_charge 12000 is outside the register map's bounds [0, 10000]", s.batteryFault());
        assertEquals(good, s.battery().orElseThrow(), "the last good reading is kept");
        s = rig.run(0.3);
        assertTrue(rig.boards.lastWrite().left() * R > 0.1, "driving on: " + rig.boards.lastWrite());
        int reads = rig.boards.batteryReads;
        rig.run(SensorRounds.BATTERY_RETRY - 0.5);
        assertEquals(reads, rig.boards.batteryReads, "a faulted board is not asked at every turn");
        rig.run(1.5);
        assertEquals(reads + 1, rig.boards.batteryReads, "asked again after the retry time");
        rig.boards.batteryFailure = null;
        s = rig.run(SensorRounds.BATTERY_RETRY + 1.0);
        assertEquals("", s.batteryFault());
        assertTrue(s.battery().orElseThrow().measured().isAfter(good.measured()));
    }

    @Test
    void beforeTheFirstReadingThereIsNoBattery() {
        ControlLoop.Snapshot s = rig.tick();
        assertTrue(s.battery().isEmpty());
        assertEquals("", s.batteryFault());
    }
}
