package sabot.control;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

import sabot.control.CollisionGuard.Action;
import sabot.control.CollisionGuard.Decision;
import sabot.control.CollisionGuard.ObstacleField;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;

/** The collision guard on hand-made obstacle fields: a wall, points, the robot's arcs forward, backward and turning. */
class CollisionGuardTest {

    /** The reference robot's figures: 0.25 m radius, 0.5 m/s², 0.5 m/s; 5 cm margin, 60 ms reaction, 0.1 m/s back. */
    private static final CollisionGuard.Settings SETTINGS = new CollisionGuard.Settings(0.25, 0.05, 0.06, 0.5, 0.5,
            0.1);
    private static final CollisionGuard GUARD = new CollisionGuard(SETTINGS);
    private static final Pose2D ORIGIN = new Pose2D(0, 0, 0);

    /** A wall across the x axis at {@code x}: everything at x and beyond is obstacle. */
    private static ObstacleField wallAt(double x) {
        return (px, py, limit) -> Math.min(limit, Math.max(0, x - px));
    }

    private static ObstacleField points(Point2D... points) {
        return (px, py, limit) -> {
            double c = limit;
            for (Point2D p : List.of(points)) {
                c = Math.min(c, Math.hypot(p.x() - px, p.y() - py));
            }
            return c;
        };
    }

    private static final ObstacleField NOTHING = (x, y, limit) -> limit;

    @Test
    void stoppingDistanceAndSpeedAreInverse() {
        for (double v : new double[] { 0.05, 0.1, 0.3, 0.5 }) {
            assertEquals(v, SETTINGS.speedFor(SETTINGS.stoppingDistance(v)), 1e-12);
        }
        assertEquals(0.5 * 0.06 + 0.25 / 1.0 + 0.05, SETTINGS.stoppingDistance(0.5), 1e-12);
        assertEquals(0, SETTINGS.speedFor(0.05));
        assertEquals(0, SETTINGS.speedFor(0));
    }

    @Test
    void openSpaceAndAFarWallLeaveTheCommandAlone() {
        Twist2D full = new Twist2D(0.5, 0.3);
        assertEquals(new Decision(full, Action.FREE, Double.POSITIVE_INFINITY), GUARD.limit(ORIGIN, full, NOTHING));
        // 1 m ahead: contact when the centre is 0.75 m on, beyond the 0.35 m the robot needs from 0.5 m/s
        Decision d = GUARD.limit(ORIGIN, new Twist2D(0.5, 0), wallAt(1.0));
        assertEquals(Action.FREE, d.action());
        assertEquals(0.5, d.twist().linear());
    }

    /** Approaching a wall, the allowed speed falls so that the robot can always stop short of it by the margin. */
    @ParameterizedTest
    @CsvSource({ "0.54", "0.50", "0.45", "0.40", "0.35", "0.32" })
    void nearAWallTheSpeedIsWhatStopsShortOfIt(double wall) {
        Decision d = GUARD.limit(ORIGIN, new Twist2D(0.5, 0.2), wallAt(wall));
        double free = wall - SETTINGS.radius();
        assertTrue(d.obstacle() <= free + 1e-9 && d.obstacle() > free - 2 * CollisionGuard.STEP, d::toString);
        assertTrue(d.twist().linear() < 0.5, d::toString);
        assertEquals(SETTINGS.speedFor(d.obstacle()), d.twist().linear(), 1e-12);
        assertTrue(SETTINGS.stoppingDistance(d.twist().linear()) <= free + 1e-12, "stops short of the wall");
        assertEquals(0.2 / 0.5, d.twist().angular() / d.twist().linear(), 1e-12, "the curvature is kept");
        assertEquals(d.twist().linear() > 0 ? Action.SLOWED : Action.STOPPED, d.action());
    }

    @Test
    void atTheMarginTheRobotStopsAndSaysWhy() {
        Decision d = GUARD.limit(ORIGIN, new Twist2D(0.3, 0.5), wallAt(0.29));
        assertEquals(Action.STOPPED, d.action());
        assertEquals(Twist2D.ZERO, d.twist());
        assertEquals("stopped: obstacle 0.04 m ahead", d.describe());
    }

    @Test
    void turningInPlaceStaysAllowedAgainstAWall() {
        Twist2D turn = new Twist2D(0, 1.2);
        assertEquals(new Decision(turn, Action.FREE, Double.POSITIVE_INFINITY), GUARD.limit(ORIGIN, turn,
                wallAt(0.26)));
    }

    @Test
    void anEchoUnderTheFootprintStopsMotionTowardsItNotAway() {
        ObstacleField behind = points(new Point2D(-0.1, 0));
        assertEquals(Action.FREE, GUARD.limit(ORIGIN, new Twist2D(0.4, 0), behind).action());
        Decision back = GUARD.limit(ORIGIN, new Twist2D(-0.1, 0), behind);
        assertEquals(Action.STOPPED, back.action());
        assertEquals("stopped: obstacle 0.00 m behind", back.describe());
    }

    @Test
    void reversingIsHeldToCreepSpeedEvenInOpenSpace() {
        Decision d = GUARD.limit(ORIGIN, new Twist2D(-0.3, 0.6), NOTHING);
        assertEquals(Action.REVERSE_CREEP, d.action());
        assertEquals(-0.1, d.twist().linear(), 1e-12);
        assertEquals(0.2, d.twist().angular(), 1e-12);
        assertEquals("reversing at 0.10 m/s: no sensor looks behind", d.describe());
        assertEquals(Action.FREE, GUARD.limit(ORIGIN, new Twist2D(-0.08, 0), NOTHING).action());
    }

    /** The arc, not the heading, is checked: a curve into a point the straight line passes by is slowed. */
    @Test
    void theCommandsArcIsChecked() {
        ObstacleField post = points(new Point2D(0.3, 0.3));
        assertEquals(Action.FREE, GUARD.limit(ORIGIN, new Twist2D(0.5, 0), post).action());
        Twist2D left = new Twist2D(0.5, 0.5 * 8 / 3); // a 0.375 m radius
        Decision curving = GUARD.limit(ORIGIN, left, post);
        assertTrue(curving.action() == Action.SLOWED || curving.action() == Action.STOPPED, curving::toString);
        assertTrue(curving.obstacle() < 0.3, curving::toString);
        // the same, the robot turned by 90°: the field is in the map frame
        ObstacleField turned = points(new Point2D(-0.3, 0.3));
        Decision rotated = GUARD.limit(new Pose2D(0, 0, Math.PI / 2), left, turned);
        assertEquals(curving.obstacle(), rotated.obstacle(), 1e-9);
    }

    /** A move judged before it starts (the PID step): the free travel along its arc, either way along it. */
    @Test
    void theFreeTravelOfAMoveFollowsItsArcAndDirection() {
        ObstacleField wall = wallAt(0.30);
        // forwards the footprint reaches the wall after 0.04 m (checked every 2 cm); backwards nothing is in the way
        assertEquals(0.04, GUARD.freeTravel(ORIGIN, new Twist2D(0.001, 0), wall), 1e-9);
        assertEquals(Double.POSITIVE_INFINITY, GUARD.freeTravel(ORIGIN, new Twist2D(-0.001, 0), wall));
        // a pivot about the right wheel (left wheel forwards) of a 0.2 m track: the same arc at any scale
        assertEquals(GUARD.freeTravel(ORIGIN, new Twist2D(0.001, -0.01), wall), GUARD.freeTravel(ORIGIN, new Twist2D(
                0.5, -5), wall), 1e-12);
        assertEquals(Double.POSITIVE_INFINITY, GUARD.freeTravel(ORIGIN, new Twist2D(0, 1), wall), "a turn in place");
        assertEquals(0, GUARD.freeTravel(ORIGIN, new Twist2D(Double.NaN, 0), wall));
    }

    @Test
    void aNonFiniteCommandIsAStop() {
        assertEquals(new Decision(Twist2D.ZERO, Action.STOPPED, 0), GUARD.limit(ORIGIN, new Twist2D(Double.NaN, 0),
                NOTHING));
    }

    @Test
    void settingsOutOfRangeAreRefused() {
        assertThrows(IllegalArgumentException.class, () -> new CollisionGuard.Settings(0, 0.05, 0.06, 0.5, 0.5, 0.1));
        assertThrows(IllegalArgumentException.class, () -> new CollisionGuard.Settings(0.25, -1, 0.06, 0.5, 0.5,
                0.1));
        assertThrows(IllegalArgumentException.class, () -> new CollisionGuard.Settings(0.25, 0.05, 0.06, 0, 0.5,
                0.1));
        assertThrows(IllegalArgumentException.class, () -> new CollisionGuard.Settings(0.25, 0.05, Double.NaN, 0.5,
                0.5, 0.1));
    }
}
