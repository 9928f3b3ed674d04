package sabot.planner;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertNotEquals;

import org.junit.jupiter.api.Test;

import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.map.Costmap;
import sabot.model.map.GridGeometry;
import sabot.planner.costmap.CostmapLayers;
import sabot.planner.costmap.InflationParameters;
import sabot.planner.costmap.MovingObstacleModel;

/** A planner re-plans on a costmap that changed in place, and its result equals planning from scratch. */
class ReplanningTest {

    @Test
    void newSonarObstacleOnThePathIsAvoidedAndTheResultEqualsAFreshPlanner() {
        GridGeometry geometry = new GridGeometry(150, 150, 0.05, Pose2D.ORIGIN);
        CostmapLayers layers = CostmapLayers.free(geometry, InflationParameters.forRobot(0.1),
                MovingObstacleModel.defaults());
        Point2D start = new Point2D(0.6, 0.6);
        Point2D goal = new Point2D(6.8, 6.8);
        Planner planner = Planners.lpn();
        PlanResult.Found before = assertInstanceOf(PlanResult.Found.class, planner.plan(layers.costmap(), start, goal));
        Point2D onPath = before.path().waypoints().get(before.path().waypoints().size() / 2);
        layers.markObstacle(onPath);
        PlanResult.Found after = assertInstanceOf(PlanResult.Found.class, planner.plan(layers.costmap(), start, goal));
        assertNotEquals(before.path(), after.path());
        PathChecks.assertCollisionFree(layers.costmap(), after.path(), start, goal, "after the new obstacle");
        PathChecks.assertDescending(after.field(), after.path(), "after the new obstacle");
        PlanResult.Found fresh = assertInstanceOf(PlanResult.Found.class,
                Planners.lpn().plan(Costmap.of(geometry, layers.costmap().toArray()), start, goal));
        assertEquals(fresh.path(), after.path(), "re-planning must give what planning from scratch gives");
    }
}
