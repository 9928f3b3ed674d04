package sabot.planner.costmap;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;

import org.junit.jupiter.api.Test;

import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.map.CellRegion;
import sabot.model.map.Costmap;
import sabot.model.map.GridGeometry;
import sabot.planner.PlanResult;
import sabot.planner.PlannedPath;
import sabot.planner.Planner;
import sabot.planner.Planners;

/** Moving obstacles raise the cost of what they will sweep, and the robot passes behind them. */
class MovingObstacleTest {

    private static final GridGeometry HALL = new GridGeometry(200, 120, 0.05, Pose2D.ORIGIN);
    private static final Point2D START = new Point2D(0.5, 3.0);
    private static final Point2D GOAL = new Point2D(9.5, 3.0);

    /** Mean y of the waypoints in the middle third of the hall, metres. */
    private static double middleY(PlannedPath path) {
        return path.waypoints().stream().filter(p -> p.x() > 4 && p.x() < 6).mapToDouble(Point2D::y).average()
                .orElseThrow();
    }

    @Test
    void pathChangesSideWhenThePersonWalksAcrossIt() {
        Planner planner = Planners.lpn();
        CostmapLayers layers = CostmapLayers.free(HALL, InflationParameters.forRobot(0.15), MovingObstacleModel.defaults());
        // a person standing a little above the straight line: the robot passes below (shorter)
        Point2D person = new Point2D(5.0, 3.3);
        layers.setMovingObstacles(List.of(new MovingObstacle(person, 0, 0, 0.25)), 0.5, 0);
        PlanResult.Found standing = assertInstanceOf(PlanResult.Found.class, planner.plan(layers.costmap(), START, GOAL));
        assertTrue(middleY(standing.path()) < 3.0, "passes below a standing person: " + middleY(standing.path()));

        // the same person walking down across the robot's way at 1 m/s: the robot passes behind, above
        layers.setMovingObstacles(List.of(new MovingObstacle(person, 0, -1.0, 0.25)), 0.5, 0);
        PlanResult.Found walking = assertInstanceOf(PlanResult.Found.class, planner.plan(layers.costmap(), START, GOAL));
        assertTrue(middleY(walking.path()) > 3.3, "passes behind a walking person: " + middleY(walking.path()));
    }

    @Test
    void sweptCostIsHighAheadLowBehindAndFadesWithDistance() {
        MovingObstacleModel model = MovingObstacleModel.defaults();
        MovingObstacle walker = new MovingObstacle(new Point2D(0, 0), 1.0, 0, 0.3);
        int ahead = model.cost(walker, 1.0, 0, 0, 0);
        int further = model.cost(walker, 2.5, 0, 0, 0);
        int behind = model.cost(walker, -1.5, 0, 0, 0);
        int aside = model.cost(walker, 1.0, 0.8, 0, 0);
        assertEquals(model.peakCost(), model.cost(walker, 0, 0, 0, 0));
        assertTrue(ahead > further && further > 0, ahead + " > " + further);
        assertEquals(0, behind);
        assertTrue(aside < ahead, "cost fades across the track");
        int closingFast = model.cost(walker, 2.0, 0, -1.0, 0);
        int closingSlow = model.cost(walker, 2.0, 0, 0.5, 0);
        assertTrue(closingFast > closingSlow, "a faster relative speed makes the swept space costlier");
    }

    @Test
    void replacingMovingObstaclesRecomputesOnlyTheirOldAndNewRegions() {
        CostmapLayers layers = CostmapLayers.free(HALL, InflationParameters.forRobot(0.15), MovingObstacleModel.defaults());
        CellRegion first = layers.setMovingObstacles(List.of(new MovingObstacle(new Point2D(2, 2), 0.5, 0, 0.2)), 0, 0);
        assertTrue(first.cellCount() < HALL.cellCount() / 4, "region " + first);
        CellRegion second = layers.setMovingObstacles(List.of(), 0, 0);
        assertEquals(first, second);
        for (int r = 0; r < HALL.height(); r++) {
            for (int c = 0; c < HALL.width(); c++) {
                assertEquals(Costmap.FREE, layers.costmap().cost(c, r));
            }
        }
    }
}
