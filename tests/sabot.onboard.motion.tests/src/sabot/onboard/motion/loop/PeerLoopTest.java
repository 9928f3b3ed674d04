package sabot.onboard.motion.loop;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.atomic.AtomicReference;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.TrajectoryPoint;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.robot.PeerRobot;
import sabot.onboard.motion.loop.ControlLoop.Mode;

/**
 * The other robots in the control loop (docs/USER-GUIDE.md, "Other robots"): the peers task's robots are planned around,
 * stop the robot when one comes onto its path, and stop the joystick short of them; a robot not heard from is
 * forgotten after the peer memory. On {@link LoopRig}: the real loop, fake boards, a fake clock.
 */
class PeerLoopTest {

    /** Centre to centre, two footprints touch at this distance. */
    private static final double TOUCH = 2 * LoopRig.ROBOT_RADIUS;

    private final LoopRig rig = new LoopRig();
    private final AtomicReference<List<PeerRobot>> peers = new AtomicReference<>(List.of());

    PeerLoopTest() {
        rig.loop.peersFrom(peers::get, () -> "sabot-01@sabot.local", new PeerSettings(5, 1.5, 120));
    }

    private PeerRobot standing(String name, double x, double y) {
        return new PeerRobot(name + "@sabot.local", new Pose2D(x, y, 0), Twist2D.ZERO, rig.clock.now(), true);
    }

    /** A robot standing in the way from the start: the plan goes round it, and the robot never touches it. */
    @Test
    void aRobotStandingOnTheWayIsPlannedAround() {
        Point2D other = new Point2D(5, 5);
        peers.set(List.of(standing("sabot-02", other.x(), other.y())));
        rig.run(0.1);
        rig.navigateTo(8, 5, 0);
        ControlLoop.Snapshot s = rig.tick();
        for (TrajectoryPoint p : s.trajectory().points()) {
            assertTrue(Math.hypot(p.x() - other.x(), p.y() - other.y()) >= TOUCH, "the plan keeps clear: " + p);
        }
        double closest = Double.POSITIVE_INFINITY;
        for (int i = 0; i < 40 * 50 && s.mission().state() == MissionState.RUNNING; i++) {
            s = rig.tick();
            rig.answerPlanRequests();
            peers.set(List.of(standing("sabot-02", other.x(), other.y()))); // heard again, at 5 Hz or so
            Pose2D p = s.pose().pose();
            closest = Math.min(closest, Math.hypot(p.x() - other.x(), p.y() - other.y()));
        }
        assertEquals(MissionState.DONE, s.mission().state(), s.mission().detail());
        assertTrue(closest >= TOUCH, "came within " + closest + " m of the other robot's centre");
    }

    /** A robot that drives onto the path ahead stops the robot, which replans round it (with the robot as obstacle). */
    @Test
    void aRobotComingOntoThePathStopsTheRobotWhichReplansAroundIt() {
        rig.run(0.1);
        rig.navigateTo(8, 5, 0);
        ControlLoop.Snapshot s = rig.run(2.0);
        assertEquals(Mode.FOLLOW, s.mode());
        List<TrajectoryPoint> before = s.trajectory().points();
        Pose2D here = s.pose().pose();
        Point2D other = new Point2D(here.x() + 1.2, here.y());
        peers.set(List.of(standing("sabot-02", other.x(), other.y())));
        s = rig.tick();
        assertEquals(Mode.BLOCKED, s.mode());
        assertEquals(1, rig.planRequests.size());
        rig.answerPlanRequests();
        s = rig.tick();
        assertNotEquals(Mode.BLOCKED, s.mode());
        List<TrajectoryPoint> after = s.trajectory().points();
        assertNotEquals(before, after);
        for (TrajectoryPoint p : after) {
            assertTrue(Math.hypot(p.x() - other.x(), p.y() - other.y()) >= TOUCH, "the new plan keeps clear: " + p);
        }
    }

    /**
     * A robot standing on the goal is not a wall that makes the goal unreachable: the robot sets off, stops short of
     * it, and arrives once it has moved away.
     */
    @Test
    void aRobotStandingOnTheGoalIsWaitedForAndNotRefused() {
        Point2D other = new Point2D(6, 5);
        peers.set(List.of(standing("sabot-02", other.x(), other.y())));
        rig.run(0.1);
        rig.navigateTo(other.x(), other.y(), 0);
        ControlLoop.Snapshot s = rig.tick();
        assertEquals(MissionState.RUNNING, s.mission().state(), s.mission().detail());
        double closest = Double.POSITIVE_INFINITY;
        for (int i = 0; i < 8 * 50; i++) {
            peers.set(List.of(standing("sabot-02", other.x(), other.y())));
            s = rig.tick();
            rig.answerPlanRequests();
            Pose2D p = s.pose().pose();
            closest = Math.min(closest, Math.hypot(p.x() - other.x(), p.y() - other.y()));
        }
        assertEquals(MissionState.RUNNING, s.mission().state(), s.mission().detail());
        assertTrue(closest >= TOUCH, "came within " + closest + " m of the robot on the goal");
        assertTrue(s.pose().pose().x() > 3, "set off towards it: " + s.pose().pose());
        peers.set(List.of()); // it drove away
        for (int i = 0; i < 30 * 50 && s.mission().state() == MissionState.RUNNING; i++) {
            s = rig.tick();
            rig.answerPlanRequests();
        }
        assertEquals(MissionState.DONE, s.mission().state(), s.mission().detail());
    }

    /**
     * The sonar's echoes off another robot's body are the robot, which the planner has already: they do not make the
     * place it is about to leave unreachable. The same echoes with no robot there do.
     */
    @Test
    void echoesOfAnotherRobotsBodyDoNotMakeItsPlaceUnreachable() {
        rig.run(0.1);
        Pose2D here = rig.loop.snapshot().pose().pose();
        Goal there = new Goal(new Pose2D(6, 5, 0), 0.05, 0.1);
        List<Point2D> echoes = List.of(new Point2D(5.76, 4.95), new Point2D(5.75, 5.0), new Point2D(5.76, 5.05));
        ControlLoop.Plan refused = rig.loop.planPath(here, new Goal(new Pose2D(5.8, 5, 0), 0.05, 0.1), echoes);
        assertNotNull(refused.refusal(), "an echo on the goal, no robot there");
        peers.set(List.of(standing("sabot-02", 6, 5)));
        ControlLoop.Plan plan = rig.loop.planPath(here, there, echoes);
        assertEquals(null, plan.refusal(), "the echoes are sabot-02's body");
    }

    /** The joystick straight at a standing robot: the collision guard stops short of its footprint. */
    @Test
    void theJoystickStopsShortOfAnotherRobot() {
        Point2D other = new Point2D(3.5, 5.0);
        rig.run(0.1);
        ControlLoop.Snapshot s = null;
        for (double t = 0; t < 6; t += 0.1) {
            peers.set(List.of(standing("sabot-02", other.x(), other.y())));
            rig.joystick(0.4, 0);
            s = rig.run(0.1);
        }
        double gap = other.x() - s.pose().pose().x() - TOUCH - PeerField.MARGIN;
        assertTrue(gap >= 0 && gap <= LoopDefaults.GUARD_MARGIN + 0.05, "gap to the other robot's disc " + gap + " m");
        assertEquals(0, rig.boards.lastWrite().left(), 1e-9);
        assertTrue(rig.loop.guardStatus().startsWith("stopped: obstacle"), rig.loop.guardStatus());
    }

    /**
     * Two robots driven straight at each other by joystick at the top speed, 0.5 m/s each: each guard brakes for the other's motion
     * as well as its own (the swept disc), so that they stop apart, where braking each for a standing robot would let
     * them meet.
     */
    @Test
    void twoRobotsDrivenAtEachOtherStopApart() {
        LoopPair p = new LoopPair(LoopRig.emptyMap(), new Pose2D(2, 5, 0), new Pose2D(6, 5, Math.PI), 10, List.of());
        for (double t = 0; t < 8; t += 0.1) {
            p.a.joystick(0.5, 0);
            p.b.joystick(0.5, 0);
            for (int i = 0; i < 5; i++) {
                p.tick();
            }
        }
        assertTrue(p.closest >= TOUCH, "they touched: centres " + p.closest + " m apart");
        assertEquals(0, p.a.boards.lastWrite().left(), 1e-9, "a stands");
        assertEquals(0, p.b.boards.lastWrite().left(), 1e-9, "b stands");
    }

    /**
     * Two robots sent to swap their places in open space meet head-on: each keeps right, they pass, and both arrive
     * without their footprints touching, hearing each other 0.2 s late. Both ways round (robot a from the west, then
     * from the east): each passes on its own right, whichever side of the map that is.
     */
    @ParameterizedTest
    @ValueSource(booleans = { true, false })
    void twoRobotsSwappingPlacesHeadOnKeepRightAndPass(boolean aFromTheWest) {
        Pose2D west = new Pose2D(2, 5, 0), east = new Pose2D(6, 5, Math.PI);
        LoopPair p = new LoopPair(LoopRig.emptyMap(), aFromTheWest ? west : east, aFromTheWest ? east : west, 10,
                List.of());
        p.tick();
        Pose2D goalA = aFromTheWest ? east : west, goalB = aFromTheWest ? west : east;
        p.send(p.a, goalA.x(), goalA.y(), goalA.theta() + Math.PI);
        p.send(p.b, goalB.x(), goalB.y(), goalB.theta() + Math.PI);
        p.runMissions(60);
        assertEquals(MissionState.DONE, p.state(p.a), p.a.loop.snapshot().mission().detail());
        assertEquals(MissionState.DONE, p.state(p.b), p.b.loop.snapshot().mission().detail());
        assertTrue(p.closest >= TOUCH + 0.1, "came within " + p.closest + " m");
        // where they met, the one heading east is south of the one heading west: each on its own right
        Pose2D[] nearest = p.poses.stream().min(java.util.Comparator.comparingDouble(two -> Math.hypot(two[0].x()
                - two[1].x(), two[0].y() - two[1].y()))).orElseThrow();
        Pose2D eastbound = aFromTheWest ? nearest[0] : nearest[1];
        Pose2D westbound = aFromTheWest ? nearest[1] : nearest[0];
        assertTrue(westbound.y() - eastbound.y() >= TOUCH, "each on its own right, a footprint apart across the way, "
                + "where they met: eastbound " + eastbound + ", westbound " + westbound);
    }

    /** Not heard from for longer than the peer memory, a robot is no obstacle any more: the joystick drives on. */
    @Test
    void aRobotNotHeardFromForThePeerMemoryIsForgotten() {
        peers.set(List.of(standing("sabot-02", 3.5, 5.0))); // heard once, now; the memory is 5 s
        rig.run(0.1);
        ControlLoop.Snapshot s = rig.drive(0.4, 0, 4);
        assertEquals(0, rig.boards.lastWrite().left(), 1e-9, "stopped by the robot heard 4 s ago");
        rig.run(1.5);
        s = rig.drive(0.4, 0, 3);
        assertTrue(s.pose().pose().x() > 3.5, "drove on through where it was: " + s.pose().pose());
    }

    /**
     * A robot heard driving is carried along its velocity for the time since (at most {@link PeerField#MAX_PREDICTION});
     * one offline stands where it was last heard.
     */
    @Test
    void aDrivingRobotIsPredictedAndAnOfflineOneStands() {
        PeerField field = new PeerField();
        Instant heard = Instant.parse("2026-11-30T12:00:00Z");
        List<PeerRobot> list = new ArrayList<>();
        list.add(new PeerRobot("a@sabot.local", new Pose2D(1, 1, Math.PI / 2), new Twist2D(0.5, 0), heard, true));
        list.add(new PeerRobot("b@sabot.local", new Pose2D(4, 1, 0), new Twist2D(0.5, 0), heard, false));
        field.from(() -> list, 30);
        List<PeerField.Disc> discs = field.discs(heard.plusMillis(400), 0.25);
        assertEquals(2, discs.size());
        assertEquals(1.0, discs.get(0).x(), 1e-9);
        assertEquals(1.2, discs.get(0).y(), 1e-9, "0.4 s at 0.5 m/s along +y");
        assertEquals(0.5, discs.get(0).vy(), 1e-9);
        assertEquals(4.0, discs.get(1).x(), 1e-9, "offline: where it was");
        assertEquals(0.0, discs.get(1).vx(), 1e-9);
        assertEquals(0.25 + PeerField.MARGIN, discs.get(1).radius(), 1e-12, "the footprint and the margin");
        PeerField.Disc late = field.discs(heard.plusSeconds(10), 0.25).get(0);
        assertEquals(1 + 0.5 * PeerField.MAX_PREDICTION, late.y(), 1e-9, "carried forward at most MAX_PREDICTION");
        assertEquals(0.0, late.vy(), 1e-9, "and taken to stand there");
        assertEquals(List.of(), field.discs(heard.plusSeconds(31), 0.25), "forgotten after the memory");
    }

    /** A source that throws gives no robots (the sonar still sees): the loop runs on. */
    @Test
    void aFailingSourceLeavesTheLoopRunning() {
        rig.loop.peersFrom(() -> {
            throw new IllegalStateException("peers task stopping");
        }, () -> "sabot-01@sabot.local", new PeerSettings(5, 1.5, 120));
        rig.run(0.1);
        rig.navigateTo(4, 5, 0);
        ControlLoop.Snapshot s = rig.run(0.5);
        assertNotNull(s.trajectory());
        assertEquals(MissionState.RUNNING, s.mission().state());
    }
}
