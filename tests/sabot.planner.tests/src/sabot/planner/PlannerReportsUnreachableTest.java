package sabot.planner;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;
import java.util.stream.Stream;

import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.Arguments;
import org.junit.jupiter.params.provider.MethodSource;

import sabot.model.geometry.Point2D;
import sabot.model.map.CellRegion;
import sabot.model.map.Costmap;

/** Every planner reports why there is no path, with the same reasons, and never loops or returns null. */
class PlannerReportsUnreachableTest {

    static Stream<Planner> planners() {
        return Planners.NAMES.stream().map(name -> Planners.byName(name, CostModel.standard()).orElseThrow());
    }

    static Stream<Arguments> cases() {
        Point2D free = new Point2D(1.5, 1.5);
        Point2D wall = new Point2D(10.5, 10.5);
        Point2D inside = new Point2D(16.5, 16.5);
        return planners().flatMap(p -> Stream.of(
                Arguments.of(p, new Point2D(-1, 3), List.of(free), UnreachableReason.START_OUTSIDE_MAP),
                Arguments.of(p, free, List.of(new Point2D(3, 20.0)), UnreachableReason.GOAL_OUTSIDE_MAP),
                Arguments.of(p, new Point2D(Double.NaN, 3), List.of(free), UnreachableReason.INVALID_REQUEST),
                Arguments.of(p, free, List.of(new Point2D(2, Double.POSITIVE_INFINITY)), UnreachableReason.INVALID_REQUEST),
                Arguments.of(p, free, List.of(), UnreachableReason.INVALID_REQUEST),
                Arguments.of(p, wall, List.of(free), UnreachableReason.START_IN_OBSTACLE),
                Arguments.of(p, free, List.of(wall), UnreachableReason.GOAL_IN_OBSTACLE),
                Arguments.of(p, free, List.of(new Point2D(12.5, 12.5)), UnreachableReason.GOAL_IN_OBSTACLE),
                Arguments.of(p, free, List.of(inside), UnreachableReason.GOAL_ENCLOSED),
                Arguments.of(p, inside, List.of(free), UnreachableReason.GOAL_ENCLOSED)));
    }

    /** 20 x 20 free map with a closed square wall (columns/rows 10..19), inscribed cell at (12, 12). */
    private static Costmap walledMap() {
        Costmap costmap = TestGrids.free(20, 20);
        costmap.fill(new CellRegion(10, 10, 19, 10), Costmap.LETHAL);
        costmap.fill(new CellRegion(10, 10, 10, 19), Costmap.LETHAL);
        costmap.set(12, 12, Costmap.INSCRIBED);
        return costmap;
    }

    @ParameterizedTest
    @MethodSource("cases")
    void plannerReportsUnreachableGoal(Planner planner, Point2D start, List<Point2D> goals, UnreachableReason reason) {
        PlanResult result = planner.plan(walledMap(), start, goals);
        PlanResult.Unreachable unreachable = assertInstanceOf(PlanResult.Unreachable.class, result, planner.name());
        assertEquals(reason, unreachable.reason(), unreachable.detail());
        assertTrue(!unreachable.detail().isBlank());
    }

    @ParameterizedTest
    @MethodSource("planners")
    void plannerReachesTheNearestOfSeveralGoals(Planner planner) {
        Costmap costmap = walledMap();
        Point2D start = new Point2D(1.5, 1.5);
        Point2D near = new Point2D(4.5, 1.5);
        Point2D far = new Point2D(1.5, 9.5);
        PlanResult.Found found = assertInstanceOf(PlanResult.Found.class, planner.plan(costmap, start, List.of(far, near)));
        assertEquals(near, found.path().end());
        PathChecks.assertCollisionFree(costmap, found.path(), start, near, planner.name());
    }

    @ParameterizedTest
    @MethodSource("planners")
    void startInTheGoalCellGivesATwoPointPath(Planner planner) {
        Point2D start = new Point2D(3.2, 3.3);
        Point2D goal = new Point2D(3.7, 3.8);
        PlanResult.Found found = assertInstanceOf(PlanResult.Found.class, planner.plan(walledMap(), start, goal));
        assertEquals(List.of(start, goal), found.path().waypoints());
    }
}
