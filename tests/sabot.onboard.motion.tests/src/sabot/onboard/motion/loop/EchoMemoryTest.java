package sabot.onboard.motion.loop;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;

import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.map.OccupancyGrid;

/**
 * The sonar's cone on the obstacle layer: the arc at the echo's range marked, the cone before it cleared, and an echo
 * the map explains (a wall in the cone at that range) marking nothing. The robot stands at (1, 5) facing +x on the
 * 10 m × 10 m map of 5 cm cells; its sensor at the centre.
 */
class EchoMemoryTest {

    private static final Pose2D ROBOT = new Pose2D(1, 5, 0);
    private static final Point2D SENSOR = new Point2D(0, 0);
    private static final double HALF_BEAM = EchoMemory.SONAR_HALF_BEAM;

    private NavigationPlanner planner;

    private EchoMemory memory(OccupancyGrid map) {
        planner = new NavigationPlanner(map, "lpn", 1, LoopRig.ROBOT_RADIUS, 0.55);
        return new EchoMemory(planner);
    }

    @AfterEach
    void close() {
        planner.close();
    }

    private static SonarPing echo(double axis, double range) {
        return new SonarPing(SENSOR, axis, range, true);
    }

    /** @return the bearing of a point from the sensor, rad */
    private static double bearing(Point2D p) {
        return Math.atan2(p.y() - ROBOT.y(), p.x() - ROBOT.x());
    }

    private static double range(Point2D p) {
        return Math.hypot(p.x() - ROBOT.x(), p.y() - ROBOT.y());
    }

    @Test
    void anEchoInOpenSpaceMarksTheArcAtItsRangeAcrossTheCone() {
        EchoMemory m = memory(LoopRig.emptyMap());
        assertTrue(m.add(0, ROBOT, echo(0, 2.0)));
        List<Point2D> marked = m.points();
        double cell = 0.05 * Math.sqrt(2) / 2;
        for (Point2D p : marked) {
            assertEquals(2.0, range(p), cell, "not on the arc: " + p);
            assertTrue(Math.abs(bearing(p)) <= HALF_BEAM + 0.02, "outside the cone: " + p);
        }
        // the whole arc, edge to edge (about 1 m of it at 2 m), not one point on the axis
        assertTrue(marked.stream().anyMatch(p -> bearing(p) > HALF_BEAM - 0.03), "left edge missing: " + marked);
        assertTrue(marked.stream().anyMatch(p -> bearing(p) < -HALF_BEAM + 0.03), "right edge missing: " + marked);
        assertTrue(marked.size() >= 18, marked.size() + " cells");
        assertEquals(0, m.nearest(3.0, 5.0, 1.0), 0.04);
        assertEquals(marked.size(), m.obstacles().size());
    }

    @Test
    void aLaterPingThatSeesFurtherClearsTheArcAndOneThatHearsNothingClearsTheCone() {
        EchoMemory m = memory(LoopRig.emptyMap());
        m.add(0, ROBOT, echo(0, 2.0));
        m.add(0.1, ROBOT, echo(0, 3.0)); // the obstacle moved away
        assertTrue(m.points().stream().allMatch(p -> Math.abs(range(p) - 3.0) < 0.05), "the 2 m arc stayed: "
                + m.points());
        m.add(0.2, ROBOT, SonarPing.silence(SENSOR, 0));
        assertTrue(m.points().isEmpty(), "a ping that heard nothing within 4 m left " + m.points());
    }

    @Test
    void aPingClearsOnlyItsOwnCone() {
        EchoMemory m = memory(LoopRig.emptyMap());
        m.add(0, ROBOT, echo(Math.toRadians(40), 1.5));
        int before = m.points().size();
        m.add(0.1, ROBOT, SonarPing.silence(SENSOR, Math.toRadians(-40)));
        assertEquals(before, m.points().size());
    }

    @Test
    void aSideWallSeenAtTheConesEdgeMarksNothing() {
        // a corridor wall 0.5 m to the left of the robot's line: the cone's left edge meets it at 0.5 / sin 15°
        OccupancyGrid map = LoopRig.emptyMap();
        int row = (int) Math.round(5.5 / 0.05);
        for (int c = 0; c < 200; c++) {
            map.set(c, row, OccupancyGrid.OCCUPIED);
        }
        EchoMemory m = memory(map);
        double edge = 0.5 / Math.sin(HALF_BEAM);
        assertFalse(m.add(0, ROBOT, echo(0, edge)), "the wall answered: " + m.points());
        assertTrue(m.points().isEmpty());
        // the board puts that echo on the axis, right on the robot's path: nothing there to stop for
        assertEquals(1.0, m.nearest(1 + edge, 5, 1.0));
    }

    @Test
    void anObstacleInFrontOfAMappedWallIsKept() {
        // the wall 2 m ahead; a crate 1.7 m ahead, 0.3 m before the wall: nearer than anything the map has in the cone
        EchoMemory m = memory(LoopRig.wallAt(3.0));
        assertTrue(m.add(0, ROBOT, echo(0, 1.7)));
        assertEquals(0, m.nearest(2.7, 5.0, 1.0), 0.04);
        // the wall itself: explained, nothing marked, and the crate's arc cleared by the ping that sees past it
        assertFalse(m.add(0.1, ROBOT, echo(0, 2.0)));
        assertTrue(m.points().isEmpty(), m.points().toString());
    }

    @Test
    void aWallSeenALittleNearerThanTheMapHasItIsStillTheWall() {
        // the estimate a few centimetres off: the wall 2 m ahead answers at 1.93 m, and 2° beside the beam
        EchoMemory m = memory(LoopRig.wallAt(3.0));
        assertFalse(m.add(0, ROBOT, echo(0, 2.0 - 0.07)), m.points().toString());
        assertTrue(m.points().isEmpty());
        // a crate 0.25 m before it is not the wall
        assertTrue(m.add(0.1, ROBOT, echo(0, 2.0 - 0.25)));
    }

    @Test
    void marksAreForgottenAfterTheMemoryUnlessSeenAgain() {
        EchoMemory m = memory(LoopRig.emptyMap());
        m.add(0, ROBOT, echo(Math.toRadians(40), 1.5));
        m.add(2, ROBOT, echo(0, 2.0));
        m.prune(3.5, 3);
        assertTrue(m.points().stream().allMatch(p -> Math.abs(bearing(p)) < Math.toRadians(20)), m.points()
                .toString());
        m.add(3.5, ROBOT, echo(0, 2.0)); // seen again: remembered anew
        m.prune(6, 3);
        assertFalse(m.points().isEmpty());
        m.prune(6.6, 3);
        assertTrue(m.points().isEmpty());
    }

    @Test
    void atMostMaxObstaclesCellsAreKeptTheOldestGoFirst() {
        EchoMemory m = memory(LoopRig.emptyMap());
        for (int i = 0; i < 400; i++) { // 400 echoes of about 4 cells each, in cones that do not overlap
            Pose2D p = new Pose2D(0.25 + (i % 20) * 0.48, 0.25 + (i / 20) * 0.48, 0);
            m.add(i, p, echo(Math.PI / 2, 0.3));
        }
        assertEquals(EchoMemory.MAX_OBSTACLES, m.points().size());
    }

    @Test
    void anotherMapDropsTheMarks() {
        EchoMemory m = memory(LoopRig.emptyMap());
        m.add(0, ROBOT, echo(0, 2.0));
        planner.replaceMap(OccupancyGrid.of(new sabot.model.map.GridGeometry(100, 100, 0.1, Pose2D.ORIGIN),
                new byte[100 * 100]));
        m.add(0.1, ROBOT, echo(Math.PI, 0.5));
        assertTrue(m.points().stream().allMatch(p -> p.x() < ROBOT.x()), m.points().toString());
    }
}
