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
import sabot.planner.costmap.MovingObstacle;
import sabot.planner.costmap.MovingObstacleModel;

/**
 * Plans on the robot's static map plus the obstacles the sonar sees: each request builds the costmap (map, sonar
 * points as lethal cells, inflation by the robot's radius) and runs the configured planner. Thread-safe: requests are
 * serialised (the planner holds its work arrays).
 */
public final class NavigationPlanner implements AutoCloseable {

    /** Occupancy (0..100) from which a map cell is a known obstacle (ROS map_server: occupied_thresh 0.65). */
    static final int OCCUPIED_THRESHOLD = 65;
    /** A robot's right-hand sweep lies this many of its diameters to its right ({@link #keepingRight}). */
    static final double KEEP_RIGHT_OFFSET = 1.0;
    /** Below this speed, m/s, a robot has no heading to keep right of: it is only its disc and its sweep. */
    static final double KEEP_RIGHT_MIN_SPEED = 0.05;
    /** Step along an imposed path at which the footprint is checked, m. */
    static final double COLLISION_STEP = 0.02;

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
    public PlanResult plan(Point2D start, Point2D goal, Collection<Point2D> obstacles) {
        return plan(start, goal, obstacles, List.of());
    }

    /**
     * Plans around the sonar's points and the other robots: each robot's disc is an obstacle (inflated by this
     * robot's radius like a wall) unless it covers the start or the goal, and the space its velocity sweeps in the next seconds costs what
     * {@link MovingObstacleModel#defaults()} gives, so that the path prefers to pass behind a robot rather than across
     * its way.
     *
     * @param obstacles sonar points in the map frame, m
     * @param robots    the other robots: centre, map-frame velocity, radius
     * @return a path or the reason there is none
     */
    public synchronized PlanResult plan(Point2D start, Point2D goal, Collection<Point2D> obstacles,
            List<MovingObstacle> robots) {
        OccupancyGrid grid = map;
        GridGeometry g = grid.geometry();
        OccupancyGrid withObstacles = OccupancyGrid.of(g, grid.toArray());
        for (Point2D p : obstacles) {
            g.cellAt(p).ifPresent(c -> withObstacles.set(c.column(), c.row(), OccupancyGrid.OCCUPIED));
        }
        for (MovingObstacle robot : robots) {
            if (!near(robot, start) && !near(robot, goal)) {
                markDisc(withObstacles, robot.position(), robot.radius());
            }
        }
        clearFootprint(withObstacles, start);
        CostmapLayers layers = CostmapLayers.fromOccupancy(withObstacles, inflation, MovingObstacleModel.defaults());
        if (!robots.isEmpty()) {
            layers.setMovingObstacles(keepingRight(robots), 0, 0);
        }
        return planner.plan(layers.costmap(), start, List.of(goal));
    }

    /**
     * Keep right, as traffic does: each robot that drives gets a second sweep beside it on its right hand (its track
     * moved {@link #KEEP_RIGHT_OFFSET} to the right), which prices the lane there, so that this robot passes it on its
     * left. Two robots meeting head-on then both turn to their own right instead of both to the same side, where they
     * would meet again.
     *
     * @return the robots and their right-hand sweeps (cost only: never walls)
     */
    static List<MovingObstacle> keepingRight(List<MovingObstacle> robots) {
        List<MovingObstacle> out = new java.util.ArrayList<>(robots);
        for (MovingObstacle r : robots) {
            double speed = r.speed();
            if (speed < KEEP_RIGHT_MIN_SPEED) {
                continue;
            }
            double offset = KEEP_RIGHT_OFFSET * 2 * r.radius();
            out.add(new MovingObstacle(new Point2D(r.position().x() + offset * r.vy() / speed, r.position().y() - offset
                    * r.vx() / speed), r.vx(), r.vy(), r.radius()));
        }
        return out;
    }

    /**
     * @return whether this robot's footprint at {@code p} would touch {@code robot}: a robot standing on the goal (it
     *         will move on: the path ahead's check stops this robot short of it until it does, or the mission fails
     *         after the blocked timeout) or next to the start is priced by its sweep only, not made a wall the planner
     *         cannot leave or reach
     */
    private boolean near(MovingObstacle robot, Point2D p) {
        return Math.hypot(robot.position().x() - p.x(), robot.position().y() - p.y()) <= robot.radius() + robotRadius;
    }

    /** Marks every cell whose centre lies within {@code radius} of {@code centre} as occupied. */
    private static void markDisc(OccupancyGrid grid, Point2D centre, double radius) {
        GridGeometry g = grid.geometry();
        Optional<Cell> middle = g.cellAt(centre);
        if (middle.isEmpty()) {
            return;
        }
        int reach = (int) Math.ceil(radius / g.resolution()) + 1;
        for (int dr = -reach; dr <= reach; dr++) {
            for (int dc = -reach; dc <= reach; dc++) {
                int c = middle.get().column() + dc;
                int r = middle.get().row() + dr;
                if (g.contains(c, r)) {
                    Point2D p = g.cellCentre(c, r);
                    if (Math.hypot(p.x() - centre.x(), p.y() - centre.y()) <= radius) {
                        grid.set(c, r, OccupancyGrid.OCCUPIED);
                    }
                }
            }
        }
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

    /**
     * @param x     map-frame x, m
     * @param y     map-frame y, m
     * @param limit distance beyond which obstacles do not matter, m
     * @return the distance from (x, y) to the nearest occupied cell of the static map (to the cell's square), m, or
     *         {@code limit} when none is nearer
     */
    public double clearance(double x, double y, double limit) {
        OccupancyGrid grid = map;
        GridGeometry g = grid.geometry();
        double res = g.resolution();
        double best = limit;
        int c0 = Math.max(0, (int) Math.floor(g.toGridX(x - limit)));
        int c1 = Math.min(g.width() - 1, (int) Math.floor(g.toGridX(x + limit)));
        int r0 = Math.max(0, (int) Math.floor(g.toGridY(y - limit)));
        int r1 = Math.min(g.height() - 1, (int) Math.floor(g.toGridY(y + limit)));
        for (int r = r0; r <= r1; r++) {
            double cellY = g.origin().y() + r * res;
            double dy = Math.max(0, Math.max(cellY - y, y - (cellY + res)));
            if (dy >= best) {
                continue;
            }
            for (int c = c0; c <= c1; c++) {
                if (grid.get(c, r) < OCCUPIED_THRESHOLD) {
                    continue;
                }
                double cellX = g.origin().x() + c * res;
                double d = Math.hypot(Math.max(0, Math.max(cellX - x, x - (cellX + res))), dy);
                if (d < best) {
                    best = d;
                }
            }
        }
        return best;
    }

    /**
     * Where a path would put the robot's footprint over an obstacle.
     *
     * @param point     index of the path's point at which the colliding segment ends (the point itself when 0)
     * @param at        the first position found in collision, map frame
     * @param clearance distance from there to the obstacle, m (less than the robot's radius)
     */
    public record Collision(int point, Point2D at, double clearance) {
    }

    /**
     * Checks a polyline (an imposed trajectory's points) every {@link #COLLISION_STEP} m along each segment: a
     * footprint of the robot's radius there must not overlap an occupied cell of the static map nor one of the
     * {@code obstacles} (sonar points).
     *
     * @return the first collision, or null when the whole path is free
     */
    public Collision firstCollision(List<Point2D> path, Collection<Point2D> obstacles) {
        for (int i = 0; i < path.size(); i++) {
            Point2D to = path.get(i);
            Point2D from = i == 0 ? to : path.get(i - 1);
            double length = Math.hypot(to.x() - from.x(), to.y() - from.y());
            int steps = Math.max(1, (int) Math.ceil(length / COLLISION_STEP));
            for (int k = i == 0 ? steps : 1; k <= steps; k++) {
                double f = (double) k / steps;
                double x = from.x() + f * (to.x() - from.x());
                double y = from.y() + f * (to.y() - from.y());
                double c = clearance(x, y, robotRadius);
                for (Point2D o : obstacles) {
                    c = Math.min(c, Math.hypot(o.x() - x, o.y() - y));
                }
                if (c < robotRadius) {
                    return new Collision(i, new Point2D(x, y), c);
                }
            }
        }
        return null;
    }

    /** @return the robot's footprint radius, m */
    public double robotRadius() {
        return robotRadius;
    }

    @Override
    public void close() {
        planner.close();
    }
}
