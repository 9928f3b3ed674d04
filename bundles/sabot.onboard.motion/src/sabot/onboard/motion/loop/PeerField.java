package sabot.onboard.motion.loop;

import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import java.util.function.Supplier;

import sabot.model.geometry.Point2D;
import sabot.model.path.Trajectory;
import sabot.model.robot.PeerRobot;
import sabot.planner.costmap.MovingObstacle;

/**
 * The other robots as obstacles (docs/USER-GUIDE.md, "Other robots"): each one the peers task follows is a disc of the
 * fleet's footprint (the robots of a fleet are of one kind: this robot's radius) plus {@link #MARGIN}, at the
 * position its telemetry last
 * gave, carried forward along its velocity for the time since, at most {@link #MAX_PREDICTION}; a robot that went
 * offline stands where it was last heard. A robot not heard for {@code memory} seconds is forgotten (the sonar still
 * sees its body). The planner takes the discs as obstacles and their predicted sweep as the moving-obstacle layer
 * ({@link NavigationPlanner}); the collision guard and the check of the path ahead take the discs.
 * <p>
 * The source and the memory are replaced from the motion task's threads; {@link #refresh} and the queries run on the
 * loop's thread, {@link #obstacles} on the planner's too.
 */
final class PeerField {

    /**
     * The longest a pose is carried forward along the peer's velocity, s: ten of its telemetry periods at the peers
     * task's 5 Hz lease. Beyond it the robot is taken to stand where the prediction ended, not to drive on.
     */
    static final double MAX_PREDICTION = 2.0;
    /**
     * What a robot's disc adds to its footprint, m: how far its true place may be from where this robot puts it — both
     * robots' pose estimates (a few centimetres each, docs/ONBOARD.md) and its motion in the up to 0.2 s between two of
     * its telemetry items at the peers task's 5 Hz that the prediction does not follow (a turn).
     */
    static final double MARGIN = 0.1;
    /**
     * How far outside a robot's disc an echo may lie and still be that robot's body, m: the sonar's arc of cells, the
     * pose estimates' errors and 0.2 s of the robot's motion between two of its telemetry items.
     */
    static final double ECHO_ALLOWANCE = 0.15;
    /**
     * How far ahead along its velocity a robot's disc is swept for the collision guard and the path-ahead check, s: the
     * time this robot takes to stop from its top speed (0.5 m/s at 0.5 m/s², docs/sabot-robot.properties). Two
     * robots driving at each other close twice as fast as one at a wall; each brakes for the room the other will
     * take meanwhile.
     */
    static final double SWEEP = 1.0;

    /** A peer as an obstacle now: its predicted centre, its map-frame velocity (0 when offline), its radius. */
    record Disc(String jid, double x, double y, double vx, double vy, double radius) {
        MovingObstacle moving() {
            return new MovingObstacle(new Point2D(x, y), vx, vy, radius);
        }
    }

    private volatile Supplier<List<PeerRobot>> source = List::of;
    private volatile double memory = LoopDefaults.PEER_MEMORY;
    /** Loop thread only: the robots at the last {@link #refresh}. */
    private List<PeerRobot> robots = List.of();
    /** Loop thread only: the discs at the last {@link #refresh}. */
    private List<Disc> discs = List.of();

    /**
     * @param source the robots followed (the peers task's snapshot); never null
     * @param memory s a robot not heard from stays an obstacle, positive
     */
    void from(Supplier<List<PeerRobot>> source, double memory) {
        if (!(memory > 0)) {
            throw new IllegalArgumentException("peer memory must be > 0 s, got " + memory);
        }
        this.source = Objects.requireNonNull(source);
        this.memory = memory;
    }

    /**
     * Loop thread: takes the peers as they are at {@code now}.
     *
     * @param radius the fleet's footprint radius, m (each disc adds {@link #MARGIN})
     * @return the discs
     */
    List<Disc> refresh(Instant now, double radius) {
        robots = read();
        discs = discs(robots, now, radius);
        return discs;
    }

    /** @return the robots as of the last {@link #refresh} */
    List<PeerRobot> robots() {
        return robots;
    }

    /** @return s a robot not heard from still counts */
    double memory() {
        return memory;
    }

    /** @return the discs of the last {@link #refresh} */
    List<Disc> current() {
        return discs;
    }

    /** Any thread: the peers' discs at {@code now}. */
    List<Disc> discs(Instant now, double radius) {
        return discs(read(), now, radius);
    }

    private List<PeerRobot> read() {
        try {
            return source.get();
        } catch (RuntimeException e) {
            return List.of(); // a failing source must not stop the loop; the sonar still sees
        }
    }

    private List<Disc> discs(List<PeerRobot> peers, Instant now, double radius) {
        if (peers.isEmpty()) {
            return List.of();
        }
        double keep = memory;
        List<Disc> out = new ArrayList<>(peers.size());
        for (PeerRobot p : peers) {
            double age = Math.max(0, Duration.between(p.heard(), now).toNanos() * 1e-9);
            if (age > keep) {
                continue;
            }
            double vx = p.online() ? p.vx() : 0;
            double vy = p.online() ? p.vy() : 0;
            double ahead = Math.min(age, MAX_PREDICTION);
            double x = p.pose().x() + vx * ahead;
            double y = p.pose().y() + vy * ahead;
            if (age >= MAX_PREDICTION) {
                vx = 0; // carried to where the prediction ends, and taken to stand there
                vy = 0;
            }
            if (Double.isFinite(x) && Double.isFinite(y)) {
                out.add(new Disc(p.jid(), x, y, vx, vy, radius + MARGIN));
            }
        }
        return out;
    }

    /**
     * The sonar's echoes that no other robot explains: an echo within {@link #ECHO_ALLOWANCE} of a robot's disc is that
     * robot's body, which the planner already has as the robot (and may plan to the place it is about to leave). The
     * collision guard and the check of the path ahead keep every echo.
     *
     * @return the echoes not on any disc, in order
     */
    static List<Point2D> unexplained(List<Point2D> echoes, List<Disc> discs) {
        if (discs.isEmpty()) {
            return echoes;
        }
        List<Point2D> out = new ArrayList<>(echoes.size());
        for (Point2D e : echoes) {
            if (nearest(discs, e.x(), e.y(), ECHO_ALLOWANCE) >= ECHO_ALLOWANCE) {
                out.add(e);
            }
        }
        return out;
    }

    /** @return the discs as the planner's moving obstacles */
    static List<MovingObstacle> obstacles(List<Disc> discs) {
        return discs.stream().map(Disc::moving).toList();
    }

    /**
     * The collision guard's and the path-ahead check's distance: to the nearest robot's disc swept along its velocity
     * for {@link #SWEEP} seconds (a capsule), so that two robots driving at each other each brake for the other's
     * motion as well as their own.
     *
     * @return the distance from (x, y) to the nearest swept disc's edge (0 inside one) of the last refresh, m, or
     *         {@code limit} when none is nearer
     */
    double nearest(double x, double y, double limit) {
        double best = limit;
        for (Disc d : discs) {
            double gap = swept(d, x, y);
            if (gap < best) {
                best = gap;
            }
        }
        return best;
    }

    /** @return the distance from (x, y) to the edge of {@code d} swept along its velocity for {@link #SWEEP} s, m */
    static double swept(Disc d, double x, double y) {
        double ex = d.vx() * SWEEP;
        double ey = d.vy() * SWEEP;
        double length2 = ex * ex + ey * ey;
        double f = length2 == 0 ? 0 : Math.max(0, Math.min(1, ((x - d.x()) * ex + (y - d.y()) * ey) / length2));
        return Math.max(0, Math.hypot(d.x() + f * ex - x, d.y() + f * ey - y) - d.radius());
    }

    static double nearest(List<Disc> discs, double x, double y, double limit) {
        double best = limit;
        for (Disc d : discs) {
            double gap = Math.max(0, Math.hypot(d.x() - x, d.y() - y) - d.radius());
            if (gap < best) {
                best = gap;
            }
        }
        return best;
    }

    /**
     * @param from      trajectory time from which to look, s
     * @param lookahead s of driving checked
     * @param clearance m a disc's edge must keep from the robot's centre on the path
     * @return the robot whose disc lies on the path ahead (as of the last refresh), or null
     */
    Disc blocking(Trajectory trajectory, double from, double lookahead, double clearance) {
        if (discs.isEmpty()) {
            return null;
        }
        for (Disc d : discs) {
            if (PathAhead.blocked(trajectory, from, lookahead, r -> swept(d, r.x(), r.y()) < clearance)) {
                return d;
            }
        }
        return null;
    }
}
