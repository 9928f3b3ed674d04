package sabot.onboard.motion.loop;

import java.util.ArrayList;
import java.util.Iterator;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

import sabot.controlml.payload.Obstacle;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.map.GridGeometry;
import sabot.model.map.OccupancyGrid;
import sabot.model.path.Trajectory;

/**
 * What the sonar saw, as an obstacle layer over the static map's grid (the costmap's raytracing, in the manner of
 * ROS's range sensor layer): each ping clears the cells of its 30° cone up to the echo — nothing nearer answered — and,
 * when the echo is not explained by the map, marks the arc of cells at its range across the cone, since the reflector
 * may be anywhere on it. An echo is explained by the map when a mapped wall lies in the cone no further than the echo's
 * range (allowing for the pose estimate's error: {@link #POSE_ALLOWANCE}, {@link #ANGLE_ALLOWANCE}): the wall answered (a side wall seen at the cone's edge, the wall ahead). An echo nearer than every mapped
 * wall in the cone is an obstacle the map does not have, even right in front of a wall. Marks are kept for the
 * obstacle memory's time unless a later ping clears them; they are reported (cm.obstacles), planned around, checked
 * against the path ahead and by the collision guard. Used by the loop's thread only.
 */
final class EchoMemory {

    /** Half-angle of a sonar's beam (HC-SR04 figures, onboard-bridge/README.md): an echo lies within it. */
    static final double SONAR_HALF_BEAM = Math.toRadians(15);
    /** The sonar's largest range, m (HC-SR04: 4 m): a ping without an echo saw nothing that near. */
    static final double SONAR_MAX_RANGE = 4.0;
    /** Largest number of marked cells kept (cm.obstacles allows 1024 rows); the oldest go first. */
    static final int MAX_OBSTACLES = 1024;
    /** Reported radius of one marked cell, m (cm.obstacles). */
    static final double ECHO_RADIUS = 0.05;
    /**
     * How much nearer than a mapped wall an echo may come and still be the wall's, m, and how far outside the beam
     * the wall may lie, rad: the pose estimate's error (a few centimetres, about a degree; docs/ONBOARD.md) and the
     * map's cells put the wall a little off where the robot believes it sees it.
     */
    static final double POSE_ALLOWANCE = 0.1;
    static final double ANGLE_ALLOWANCE = Math.toRadians(2);

    private final NavigationPlanner planner;
    /** The grid the marks index: the static map's; marks are dropped when the map changes. */
    private GridGeometry geometry;
    /** Marked cells: grid index to the time of the last echo that marked it, oldest first. */
    private final LinkedHashMap<Integer, Double> marks = new LinkedHashMap<>();

    /** @param planner knows the static map, whose walls the sonar need not report again */
    EchoMemory(NavigationPlanner planner) {
        this.planner = planner;
    }

    /**
     * The band around an echo's range that it marks and that the map must reach to explain it, m: three sigmas of the
     * board's range noise (3 mm + 0.5 % of the range, onboard-bridge/README.md), at least two cells.
     */
    static double band(double range, double resolution) {
        return Math.max(2 * resolution, 3 * (0.003 + 0.005 * range));
    }

    /**
     * Takes one ping seen at {@code t} from {@code pose}.
     *
     * @return whether it marked cells (an obstacle the map does not have)
     */
    boolean add(double t, Pose2D pose, SonarPing ping) {
        OccupancyGrid map = planner.map();
        GridGeometry g = map.geometry();
        if (!g.equals(geometry)) {
            marks.clear();
            geometry = g;
        }
        double c = Math.cos(pose.theta());
        double s = Math.sin(pose.theta());
        double ox = pose.x() + c * ping.origin().x() - s * ping.origin().y();
        double oy = pose.y() + s * ping.origin().x() + c * ping.origin().y();
        double axis = pose.theta() + ping.axis();
        double res = g.resolution();
        double band = band(ping.range(), res);
        double clearTo = ping.echo() ? ping.range() - band : ping.range();
        if (clearTo > 0) {
            Cone cone = new Cone(axis, clearTo, res);
            for (int i = 0; i < cone.rays; i++) {
                double a = cone.angle(i);
                double dx = Math.cos(a);
                double dy = Math.sin(a);
                for (double d = 0; d < clearTo; d += res / 2) {
                    int index = index(g, ox + d * dx, oy + d * dy);
                    if (index >= 0) {
                        marks.remove(index);
                    }
                }
            }
        }
        if (!ping.echo() || wallWithin(map, ox, oy, axis, ping.range() + band + POSE_ALLOWANCE)) {
            return false;
        }
        Cone arc = new Cone(axis, ping.range(), res);
        boolean marked = false;
        for (int i = 0; i < arc.rays; i++) {
            double a = arc.angle(i);
            int index = index(g, ox + ping.range() * Math.cos(a), oy + ping.range() * Math.sin(a));
            if (index >= 0) {
                marks.remove(index); // marked again: now the newest
                marks.put(index, t);
                marked = true;
            }
        }
        while (marks.size() > MAX_OBSTACLES) {
            marks.pollFirstEntry();
        }
        return marked;
    }

    /** Rays across a cone, spaced so that neighbours are at most half a cell apart at its far end. */
    private static final class Cone {
        final double axis;
        final double half;
        final int rays;

        Cone(double axis, double range, double resolution) {
            this(axis, SONAR_HALF_BEAM, range, resolution);
        }

        Cone(double axis, double half, double range, double resolution) {
            this.axis = axis;
            this.half = half;
            this.rays = 1 + Math.max(6, (int) Math.ceil(2 * half * range / (resolution / 2)));
        }

        double angle(int i) {
            return axis - half + 2 * half * i / (rays - 1);
        }
    }

    /**
     * @return whether an occupied cell of the static map (or the map's edge) lies in the cone, widened by
     *         {@link #ANGLE_ALLOWANCE}, within {@code range}
     */
    private static boolean wallWithin(OccupancyGrid map, double ox, double oy, double axis, double range) {
        GridGeometry g = map.geometry();
        double res = g.resolution();
        Cone cone = new Cone(axis, SONAR_HALF_BEAM + ANGLE_ALLOWANCE, range, res);
        for (int i = 0; i < cone.rays; i++) {
            double a = cone.angle(i);
            double dx = Math.cos(a);
            double dy = Math.sin(a);
            for (double d = 0; d <= range; d += res / 2) {
                int col = (int) Math.floor(g.toGridX(ox + d * dx));
                int row = (int) Math.floor(g.toGridY(oy + d * dy));
                if (!g.contains(col, row) || map.get(col, row) >= NavigationPlanner.OCCUPIED_THRESHOLD) {
                    return true;
                }
            }
        }
        return false;
    }

    /** @return the cell's index in {@code g}, or -1 outside the grid */
    private static int index(GridGeometry g, double x, double y) {
        int col = (int) Math.floor(g.toGridX(x));
        int row = (int) Math.floor(g.toGridY(y));
        return g.contains(col, row) ? g.index(col, row) : -1;
    }

    private Point2D centre(int index) {
        return geometry.cellCentre(index % geometry.width(), index / geometry.width());
    }

    /** Forgets the marks older than {@code memory} seconds at {@code t}. */
    void prune(double t, double memory) {
        Iterator<Map.Entry<Integer, Double>> it = marks.entrySet().iterator();
        while (it.hasNext() && t - it.next().getValue() > memory) {
            it.remove();
        }
    }

    /**
     * @param from      trajectory time from which to look, s
     * @param lookahead s of driving checked
     * @param clearance m a mark must keep from the robot's centre on the path
     * @return whether a marked cell lies on the path ahead
     */
    boolean blocks(Trajectory trajectory, double from, double lookahead, double clearance) {
        if (marks.isEmpty()) {
            return false;
        }
        return PathAhead.blocked(trajectory, from, lookahead, r -> nearest(r.x(), r.y(), clearance) < clearance);
    }

    /** @return the distance from (x, y) to the nearest marked cell's centre, m, or {@code limit} when none is nearer */
    double nearest(double x, double y, double limit) {
        double best = limit;
        if (marks.isEmpty()) {
            return best;
        }
        int width = geometry.width();
        double res = geometry.resolution();
        double x0 = geometry.origin().x() + res / 2;
        double y0 = geometry.origin().y() + res / 2;
        for (int index : marks.keySet()) {
            double d = Math.hypot(x0 + (index % width) * res - x, y0 + (index / width) * res - y);
            if (d < best) {
                best = d;
            }
        }
        return best;
    }

    /** @return the marked cells' centres, for the planner */
    List<Point2D> points() {
        List<Point2D> points = new ArrayList<>(marks.size());
        for (int index : marks.keySet()) {
            points.add(centre(index));
        }
        return points;
    }

    /** @return the marked cells as reported obstacles */
    List<Obstacle> obstacles() {
        List<Obstacle> obstacles = new ArrayList<>(marks.size());
        for (int index : marks.keySet()) {
            Point2D p = centre(index);
            obstacles.add(new Obstacle(p.x(), p.y(), ECHO_RADIUS));
        }
        return obstacles;
    }
}
