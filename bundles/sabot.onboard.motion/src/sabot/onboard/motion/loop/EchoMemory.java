package sabot.onboard.motion.loop;

import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Deque;
import java.util.List;

import sabot.controlml.payload.Obstacle;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.path.Trajectory;
import sabot.model.path.TrajectorySample;

/**
 * The sonar echoes the loop remembers, in the map frame: those near a wall the map already has are dropped, the rest
 * are kept for the obstacle memory's time, reported (cm.obstacles), planned around, and checked against the path
 * ahead. Used by the loop's thread only.
 */
final class EchoMemory {

    /** Half-angle of a sonar's beam (HC-SR04 figures, onboard-bridge/README.md): an echo lies within it. */
    static final double SONAR_HALF_BEAM = Math.toRadians(15);
    /** Largest number of obstacle points kept (cm.obstacles allows 1024 rows). */
    static final int MAX_OBSTACLES = 1024;
    /** Reported radius of one sonar obstacle point, m (one echo: the sonar's resolution, not the object's size). */
    static final double ECHO_RADIUS = 0.05;
    /** Step along the trajectory ahead at which it is checked against the echoes, s. */
    private static final double BLOCKED_CHECK_STEP = 0.1;

    private final NavigationPlanner planner;
    /** Each echo as {time s, x m, y m}, oldest first. */
    private final Deque<double[]> echoes = new ArrayDeque<>();

    /** @param planner knows the static map, whose walls the sonar need not report again */
    EchoMemory(NavigationPlanner planner) {
        this.planner = planner;
    }

    /**
     * Remembers one echo seen at {@code t} from {@code pose}.
     *
     * @param robotFrame the echo in the robot frame, m
     */
    void add(double t, Pose2D pose, Point2D robotFrame) {
        double c = Math.cos(pose.theta());
        double s = Math.sin(pose.theta());
        Point2D p = new Point2D(pose.x() + c * robotFrame.x() - s * robotFrame.y(),
                pose.y() + s * robotFrame.x() + c * robotFrame.y());
        // the board puts an echo on the beam's axis; the reflector may be anywhere across the beam at that range
        double across = Math.hypot(robotFrame.x(), robotFrame.y()) * Math.sin(SONAR_HALF_BEAM);
        if (planner.isNearStaticObstacle(p, across)) {
            return;
        }
        echoes.addLast(new double[] { t, p.x(), p.y() });
        while (echoes.size() > MAX_OBSTACLES) {
            echoes.removeFirst();
        }
    }

    /** Forgets the echoes older than {@code memory} seconds at {@code t}. */
    void prune(double t, double memory) {
        while (!echoes.isEmpty() && t - echoes.peekFirst()[0] > memory) {
            echoes.removeFirst();
        }
    }

    /**
     * @param from      trajectory time from which to look, s
     * @param lookahead s of driving checked
     * @param clearance m an echo must keep from the robot's centre on the path
     * @return whether an echo lies on the path ahead
     */
    boolean blocks(Trajectory trajectory, double from, double lookahead, double clearance) {
        if (echoes.isEmpty()) {
            return false;
        }
        double end = Math.min(trajectory.duration(), from + lookahead);
        for (double s = from; s <= end; s += BLOCKED_CHECK_STEP) {
            TrajectorySample r = trajectory.sample(s);
            for (double[] e : echoes) {
                if (Math.hypot(e[1] - r.x(), e[2] - r.y()) < clearance) {
                    return true;
                }
            }
        }
        return false;
    }

    /** @return the distance from (x, y) to the nearest echo, m, or {@code limit} when none is nearer */
    double nearest(double x, double y, double limit) {
        double best = limit;
        for (double[] e : echoes) {
            double d = Math.hypot(e[1] - x, e[2] - y);
            if (d < best) {
                best = d;
            }
        }
        return best;
    }

    /** @return the echoes as points, for the planner */
    List<Point2D> points() {
        List<Point2D> points = new ArrayList<>(echoes.size());
        for (double[] e : echoes) {
            points.add(new Point2D(e[1], e[2]));
        }
        return points;
    }

    /** @return the echoes as reported obstacles */
    List<Obstacle> obstacles() {
        List<Obstacle> obstacles = new ArrayList<>(echoes.size());
        for (double[] e : echoes) {
            obstacles.add(new Obstacle(e[1], e[2], ECHO_RADIUS));
        }
        return obstacles;
    }
}
