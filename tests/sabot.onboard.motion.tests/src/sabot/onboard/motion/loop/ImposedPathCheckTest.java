package sabot.onboard.motion.loop;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;

import org.junit.jupiter.api.Test;

import sabot.model.geometry.Point2D;

/**
 * An imposed trajectory's points checked against the robot's footprint before it is accepted: the static map's walls
 * and the sonar's points, along every segment, not only at the points.
 */
class ImposedPathCheckTest {

    /** A wall whose near face is at x = 4 m across the 10 m × 10 m map; the robot's radius 0.25 m. */
    private final NavigationPlanner planner = new NavigationPlanner(LoopRig.wallAt(4.0), "lpn", 1,
            LoopRig.ROBOT_RADIUS, 0.55);

    @Test
    void aSegmentThroughTheWallCollidesWhereTheFootprintFirstReachesIt() {
        // both points are free: only the segment between them crosses the wall
        NavigationPlanner.Collision c = planner.firstCollision(List.of(new Point2D(2, 5), new Point2D(2.5, 5),
                new Point2D(6, 5)), List.of());
        assertNotNull(c);
        assertEquals(2, c.point());
        assertEquals(5, c.at().y(), 1e-9);
        assertTrue(c.at().x() > 4.0 - LoopRig.ROBOT_RADIUS && c.at().x() < 4.0 - LoopRig.ROBOT_RADIUS + 0.03,
                c::toString);
        assertTrue(c.clearance() < LoopRig.ROBOT_RADIUS, c::toString);
    }

    @Test
    void aFreeCorridorAlongTheWallIsAccepted() {
        assertNull(planner.firstCollision(List.of(new Point2D(2, 5), new Point2D(3.7, 5), new Point2D(3.7, 8)),
                List.of()));
    }

    @Test
    void aSonarPointOnThePathCollides() {
        NavigationPlanner.Collision c = planner.firstCollision(List.of(new Point2D(2, 5), new Point2D(3.5, 5)),
                List.of(new Point2D(3.0, 5.1)));
        assertNotNull(c);
        assertEquals(1, c.point());
        assertTrue(Math.hypot(c.at().x() - 3.0, c.at().y() - 5.1) < LoopRig.ROBOT_RADIUS, c::toString);
    }

    @Test
    void aFirstPointInsideTheWallCollidesAtItself() {
        NavigationPlanner.Collision c = planner.firstCollision(List.of(new Point2D(4.02, 5), new Point2D(2, 5)),
                List.of());
        assertNotNull(c);
        assertEquals(0, c.point());
        assertEquals(0, c.clearance(), 1e-9);
    }
}
