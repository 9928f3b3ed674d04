package sabot.onboard.motion.loop;

import java.util.Collection;
import java.util.List;
import java.util.Optional;

import sabot.model.geometry.Point2D;
import sabot.model.map.Cell;
import sabot.model.map.GridGeometry;
import sabot.model.map.OccupancyGrid;
import sabot.planner.CostModel;
import sabot.planner.PlanResult;
import sabot.planner.Planner;
import sabot.planner.Planners;
import sabot.planner.costmap.CostmapLayers;
import sabot.planner.costmap.InflationParameters;
import sabot.planner.costmap.MovingObstacleModel;

/**
 * Plans on the robot's static map plus the obstacles the sonar sees: each request builds the costmap (map, sonar
 * points as lethal cells, inflation by the robot's radius) and runs the configured planner. Thread-safe: requests are
 * serialised (the planner holds its work arrays).
 */
public final class NavigationPlanner implements AutoCloseable {

    /** Occupancy (0..100) from which a map cell is a known obstacle (ROS map_server: occupied_thresh 0.65). */
    private static final int OCCUPIED_THRESHOLD = 65;

    private final Planner planner;
    private final InflationParameters inflation;
    private final double robotRadius;
    private volatile OccupancyGrid map;

    public NavigationPlanner(OccupancyGrid map, String algorithm, int threads, double robotRadius, double inflationRadius) {
        this.map = map;
        this.planner = Planners.byName(algorithm, CostModel.standard(), threads).orElseThrow(
                () -> new IllegalArgumentException("unknown planner '" + algorithm + "', one of " + Planners.NAMES));
        this.robotRadius = robotRadius;
        this.inflation = InflationParameters.forRobot(robotRadius).withDecay(Math.max(inflationRadius, robotRadius),
                InflationParameters.DEFAULT_COST_SCALING_FACTOR);
    }

    /** @return the static map (a copy is not made: callers must not change it) */
    public OccupancyGrid map() {
        return map;
    }

    /** Replaces the static map. */
    public void replaceMap(OccupancyGrid newMap) {
        this.map = newMap;
    }

    /** @return the planner's name, e.g. lpn */
    public String algorithm() {
        return planner.name();
    }

    /**
     * @param obstacles sonar points in the map frame, m
     * @return a path or the reason there is none
     */
    public synchronized PlanResult plan(Point2D start, Point2D goal, Collection<Point2D> obstacles) {
        OccupancyGrid grid = map;
        OccupancyGrid withObstacles = OccupancyGrid.of(grid.geometry(), grid.toArray());
        for (Point2D p : obstacles) {
            grid.geometry().cellAt(p).ifPresent(c -> withObstacles.set(c.column(), c.row(), OccupancyGrid.OCCUPIED));
        }
        clearFootprint(withObstacles, start);
        CostmapLayers layers = CostmapLayers.fromOccupancy(withObstacles, inflation, MovingObstacleModel.defaults());
        return planner.plan(layers.costmap(), start, List.of(goal));
    }

    /**
     * The robot stands where it stands: unknown cells and sonar echoes under its footprint are free (as Nav2 clears
     * the footprint), so that a robot that drove onto the edge of an unmapped area, or whose sonar saw its own
     * surroundings, can plan away. Walls of the static map stay.
     */
    private void clearFootprint(OccupancyGrid grid, Point2D start) {
        GridGeometry g = grid.geometry();
        Optional<Cell> centre = g.cellAt(start);
        if (centre.isEmpty()) {
            return;
        }
        int reach = (int) Math.ceil(robotRadius / g.resolution());
        OccupancyGrid staticMap = map;
        for (int dr = -reach; dr <= reach; dr++) {
            for (int dc = -reach; dc <= reach; dc++) {
                int c = centre.get().column() + dc;
                int r = centre.get().row() + dr;
                if (g.contains(c, r) && Math.hypot(dc, dr) * g.resolution() <= robotRadius
                        && staticMap.get(c, r) < OCCUPIED_THRESHOLD) {
                    grid.set(c, r, OccupancyGrid.FREE);
                }
            }
        }
    }

    /**
     * @return true when an occupied cell of the static map lies within {@code radius} (m, plus one cell) of {@code p}:
     *         a sonar echo that may come from a wall the planner already knows
     */
    public boolean isNearStaticObstacle(Point2D p, double radius) {
        OccupancyGrid grid = map;
        GridGeometry g = grid.geometry();
        Optional<Cell> cell = g.cellAt(p);
        if (cell.isEmpty()) {
            return true;
        }
        int reach = 1 + (int) Math.ceil(radius / g.resolution());
        double limit = radius + g.resolution();
        for (int dr = -reach; dr <= reach; dr++) {
            for (int dc = -reach; dc <= reach; dc++) {
                int c = cell.get().column() + dc;
                int r = cell.get().row() + dr;
                if (g.contains(c, r) && grid.get(c, r) >= OCCUPIED_THRESHOLD
                        && Math.hypot(dc, dr) * g.resolution() <= limit) {
                    return true;
                }
            }
        }
        return false;
    }

    @Override
    public void close() {
        planner.close();
    }
}
