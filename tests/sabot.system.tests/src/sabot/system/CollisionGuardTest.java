package sabot.system;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;
import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.TimeUnit;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.TrajectoryPayload;
import sabot.controlml.payload.TrajectoryPoint;
import sabot.controlml.payload.VelocityCommand;
import sabot.model.geometry.Twist2D;
import sabot.testsupport.robot.SimProcess;

/**
 * The collision guard on the running robot, judged on the simulator's truth: a joystick held towards the lab's
 * partition (a wall of the map), towards a crate that is on no map and towards a standing robot (only the sonar sees
 * them) stops the robot short of each without a contact; until an obstacle is within its stopping distance the
 * joystick's speed is not cut. An imposed trajectory through a wall is refused, a free one followed.
 */
class CollisionGuardTest extends RigTest {

    /** The robot's top speed, m/s (docs/sabot-robot.properties). */
    static final double TOP_SPEED = 0.5;
    /** The robot's footprint radius, m (the planner's default). */
    static final double RADIUS = 0.25;
    /**
     * Largest gap at which the robot may stand when it stops for an obstacle, m: the guard's margin (0.05 m), one step
     * of its arc check (0.02 m), the estimate's error and the last period's travel.
     */
    static final double GAP_BOUND = 0.15;
    /** s of the simulator's clock the robot stands with the joystick pushing before it counts as stopped. */
    static final double PUSHED_STILL = 0.5;

    @Test
    void joystickTowardsTheMappedPartitionStopsShortOfIt(@TempDir Path dir) throws Exception {
        // the partition's west face is at x = 3.0 m; the robot starts at x = 1.5 m facing it
        try (RobotRig rig = RobotRig.start(xmpp, dir, WEST_OF_PARTITION, new String[0], "")) {
            SimProcess.Truth stopped = holdJoystick(rig, TOP_SPEED, 8);
            double gap = 3.0 - (stopped.x() + RADIUS);
            System.out.printf(Locale.ROOT, "[figure] collision guard, joystick at %.1f m/s towards the partition (a "
                    + "wall of the map): stopped %.3f m short, contacts %d%n", TOP_SPEED, gap, stopped.contacts());
            assertEquals(0, stopped.contacts(), "touched the partition: " + stopped);
            assertEquals(0, rig.sim.contactsInTruthFile(), "the truth file records a contact");
            assertTrue(gap >= 0 && gap <= GAP_BOUND, "stopped " + gap + " m short of the partition");
            rig.onboard.await(l -> l.contains("collision guard: stopped: obstacle"), "saying why it stopped");
        }
    }

    /**
     * A crate on no map, seen only by the sonar, in front of the robot, approached by joystick at 0.1, 0.3 and 0.5 m/s
     * in turn (the crate moved ahead again between runs); prints the figures of docs/ONBOARD.md. The free way ahead
     * grows with the speed: room to reach it (at 0.5 m/s², 0.25 m at the top speed) before the guard's stopping
     * distance (0.35 m at the top speed) begins to cut it.
     */
    @Test
    void joystickTowardsACrateOnNoMapStopsShortOfItAtEverySpeed(@TempDir Path dir) throws Exception {
        double crateRadius = 0.2;
        double[][] runs = { { 0.1, 0.4 }, { 0.3, 0.7 }, { 0.5, 1.0 } }; // speed m/s, free way ahead m
        try (RobotRig rig = RobotRig.start(xmpp, dir, CORRIDOR_WEST, new String[0], "")) {
            for (int run = 0; run < runs.length; run++) {
                double speed = runs[run][0];
                double freeAhead = runs[run][1];
                SimProcess.Truth start = rig.sim.truth();
                double crateX = start.x() + RADIUS + freeAhead + crateRadius;
                rig.sim.command(run == 0 ? String.format(Locale.ROOT, "obstacle add crate %.3f 1.00 %.2f", crateX,
                        crateRadius) : String.format(Locale.ROOT, "obstacle move crate %.3f 1.00", crateX));
                if (run > 0) {
                    // the echoes of the crate where it stood leave the obstacle memory (3 s)
                    awaitSimTime(rig.sim, 3.5);
                }
                double[] top = { 0 };
                SimProcess.Truth stopped = holdJoystick(rig, speed, freeAhead / speed + 3, top);
                double gap = crateX - crateRadius - (stopped.x() + RADIUS);
                System.out.printf(Locale.ROOT, "[figure] collision guard, joystick at %.1f m/s towards a crate seen "
                        + "by the sonar alone: top speed %.3f m/s, stopped %.3f m short, contacts %d%n", speed, top[0],
                        gap, stopped.contacts());
                assertEquals(0, stopped.contacts(), "touched the crate at " + speed + " m/s: " + stopped);
                assertTrue(gap >= 0 && gap <= GAP_BOUND, "stopped " + gap + " m short of the crate at " + speed
                        + " m/s");
                // until the crate is within its stopping distance the guard leaves the joystick alone: the commanded
                // speed is reached (at the top speed, the metre leaves the guard little room: 0.27 m/s at least)
                double reached = speed < TOP_SPEED ? 0.95 * speed : 0.27;
                assertTrue(top[0] >= reached, "the guard cut the approach at " + speed + " m/s: top " + top[0]);
            }
            assertEquals(0, rig.sim.contactsInTruthFile(), "the truth file records a contact");
        }
    }

    /**
     * A second robot of the simulator stands 0.8 m ahead (centre to centre; the simulator puts robot 2 there): only
     * the sonar sees it, as a crate. The joystick at the top speed stops the robot short of it without a contact.
     */
    @Test
    void joystickTowardsAStandingRobotStopsShortOfIt(@TempDir Path dir) throws Exception {
        double[] start = { WEST_OF_PARTITION[0], WEST_OF_PARTITION[1], Math.PI / 2 };
        try (RobotRig rig = RobotRig.start(xmpp, dir, start, new String[] { "--robots", "2" }, "")) {
            SimProcess.Truth other = rig.sim.truth(2);
            SimProcess.Truth stopped = holdJoystick(rig, TOP_SPEED, 4);
            double gap = stopped.distanceTo(other.x(), other.y()) - 2 * RADIUS;
            System.out.printf(Locale.ROOT, "[figure] collision guard, joystick at %.1f m/s towards a standing robot: "
                    + "stopped %.3f m short, contacts %d%n", TOP_SPEED, gap, stopped.contacts());
            assertEquals(0, stopped.contacts(), "touched the other robot: " + stopped);
            assertEquals(0, rig.sim.contactsInTruthFile(), "the truth file records a contact");
            assertTrue(gap >= 0 && gap <= GAP_BOUND, "stopped " + gap + " m short of the other robot");
            SimProcess.Truth still = rig.sim.truth(2);
            assertTrue(still.distanceTo(other.x(), other.y()) < 0.005, "the other robot was pushed: " + still);
        }
    }

    /**
     * An imposed {@code cm.trajectory} is checked against the map like the joystick: one through the partition is
     * refused with {@code invalid-value} naming its first colliding point, and the robot does not move; one that
     * stops short of the partition is followed, and the robot ends where it ends.
     */
    @Test
    void anImposedTrajectoryThroughTheWallIsRefusedAndAFreeOneIsFollowed(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, WEST_OF_PARTITION, new String[0], "")) {
            SimProcess.Truth before = rig.sim.truth();
            Outcome<TrajectoryPayload> through = rig.operator.set(rig.robot, Resources.TRAJECTORY, eastward(
                    WEST_OF_PARTITION[0], 4.5, WEST_OF_PARTITION[1]));
            assertEquals(ControlMlCondition.INVALID_VALUE, through.errorOrNull().cmCondition(), through.toString());
            assertTrue(through.errorOrNull().text().matches("trajectory point \\d+ .* collides: .*"), through
                    .errorOrNull().text());
            SimProcess.Truth still = awaitSimTime(rig.sim, 1.5);
            assertTrue(still.distanceTo(before.x(), before.y()) < 0.01, "moved on a refused trajectory: " + still);

            double end = 3.0 - RADIUS - 0.2; // 0.2 m short of the partition's face
            assertTrue(rig.operator.set(rig.robot, Resources.TRAJECTORY, eastward(WEST_OF_PARTITION[0], end,
                    WEST_OF_PARTITION[1])).isSuccess(), rig.onboard.output());
            SimProcess.Truth there = awaitTruth(rig.sim, t -> t.x() > end - 0.1 && Math.abs(t.v()) < 0.01, 20,
                    "the robot at the trajectory's end");
            assertEquals(0, there.contacts(), there.toString());
        }
    }

    /** @return a trajectory due east at 0.2 m/s from (x0, y) to (x1, y), a point every 0.1 s, starting now */
    private static TrajectoryPayload eastward(double x0, double x1, double y) {
        double v = 0.2;
        List<TrajectoryPoint> points = new ArrayList<>();
        int n = (int) Math.ceil((x1 - x0) / v / 0.1);
        for (int i = 0; i <= n; i++) {
            double t = Math.min(i * 0.1, (x1 - x0) / v);
            points.add(new TrajectoryPoint(t, x0 + v * t, y, 0, i == n ? 0 : v, 0));
        }
        return new TrajectoryPayload(Instant.now(), points);
    }

    private static void twist(RobotRig rig, double speed) throws Exception {
        assertTrue(rig.operator.set(rig.robot, Resources.VELOCITY, new VelocityCommand(Instant.now(), new Twist2D(
                speed, 0))).isSuccess(), rig.onboard.output());
        TimeUnit.MILLISECONDS.sleep(1000 / JOYSTICK_HZ); // the stimulus: a joystick at 10 Hz
    }

    private static SimProcess.Truth holdJoystick(RobotRig rig, double speed, double seconds) throws Exception {
        return holdJoystick(rig, speed, seconds, new double[1]);
    }

    /**
     * Holds the joystick forward until the robot stands before an obstacle and the guard says so: the robot has stood
     * for {@link #PUSHED_STILL} s of the simulator's clock with the joystick still pushing, and the operator reads
     * {@code stopped: obstacle …} in {@code cm.mission}. A standstill for another reason (a deadman stop between two
     * late twists of a starved test) does not end it.
     *
     * @param seconds the joystick's time, at 10 Hz, to reach any obstacle in front: past it the robot still driving or
     *                standing without the guard's word is the failure
     * @param top     receives the top true speed seen while the joystick was held
     * @return the truth at standstill
     */
    private static SimProcess.Truth holdJoystick(RobotRig rig, double speed, double seconds, double[] top)
            throws Exception {
        double stillSince = Double.NaN;
        SimProcess.Truth truth = null;
        String guard = "(not asked)";
        for (int i = 0; i < seconds * JOYSTICK_HZ; i++) {
            twist(rig, speed);
            truth = rig.sim.truth();
            top[0] = Math.max(top[0], truth.v());
            if (Math.abs(truth.v()) >= 0.005 || Math.abs(truth.omega()) >= 0.01) {
                stillSince = Double.NaN;
            } else if (Double.isNaN(stillSince)) {
                stillSince = truth.t();
            } else if (truth.t() - stillSince >= PUSHED_STILL) {
                MissionStatus m = rig.get(Resources.MISSION);
                guard = m.detail();
                if (guard.startsWith("stopped: obstacle")) {
                    return truth;
                }
            }
        }
        throw new AssertionError(String.format(Locale.ROOT, "after %.1f s of the joystick at %.1f m/s the robot does "
                + "not stand before an obstacle with the guard's word for it: truth %s, cm.mission detail \"%s\"",
                seconds, speed, truth, guard));
    }
}
