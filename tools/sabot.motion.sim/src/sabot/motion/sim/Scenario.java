package sabot.motion.sim;

import java.util.ArrayList;
import java.util.List;
import java.util.Locale;

import sabot.control.MotionLimits;
import sabot.control.trajectory.SplineTrajectory;
import sabot.control.trajectory.TrajectorySequence;
import sabot.control.trajectory.TurnInPlaceTrajectory;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.path.Trajectory;

/** The simulated scenarios. */
public enum Scenario {
    /** Bernoulli lemniscate with 2.5 m lobes (a = 2.5 m, 13.1 m per lap) at 0.3 m/s: the thesis's figure-eight. */
    LEMNISCATE(true),
    /** Circle of radius 1 m at 0.3 m/s, one lap. */
    CIRCLE(true),
    /** 2 m square, counter-clockwise, stopping and turning on the spot at each corner. */
    SQUARE(true),
    /** The lemniscate started 0.3 m, 0.3 m and 30 degrees off the reference's start pose. */
    OFFSET(false),
    /** Point stabilization to the origin from 20 random starts. */
    STABILIZE(false);

    /** Lemniscate half-width a, metres: each lobe is 2.5 m long. */
    public static final double LEMNISCATE_A = 2.5;
    public static final double CRUISE_SPEED = 0.3;
    public static final double CIRCLE_RADIUS = 1.0;
    public static final double SQUARE_SIDE = 2.0;
    public static final Pose2D OFFSET_ERROR = new Pose2D(0.3, 0.3, Math.toRadians(30));

    private final boolean closed;

    Scenario(boolean closed) {
        this.closed = closed;
    }

    /** @return true when the robot should come back to where it started (return error is meaningful) */
    public boolean isClosed() {
        return closed;
    }

    /** @return the command-line spelling */
    public String cliName() {
        return name().toLowerCase(Locale.ROOT);
    }

    /** Fraction of the robot's speed and acceleration limits the planner may use; the rest is feedback authority. */
    public static final double PLANNING_HEADROOM = 0.8;

    /** @return the reference trajectory of a tracking scenario, planned within {@link #PLANNING_HEADROOM} of the limits */
    public Trajectory trajectory(MotionLimits robotLimits) {
        return trajectory(robotLimits, false);
    }

    /**
     * @param fromVertex start the lemniscate at its vertex instead of its crossing point (ignored by other scenarios)
     * @return the reference trajectory, planned within {@link #PLANNING_HEADROOM} of the limits
     */
    public Trajectory trajectory(MotionLimits robotLimits, boolean fromVertex) {
        MotionLimits limits = robotLimits.withHeadroom(PLANNING_HEADROOM);
        return switch (this) {
            case LEMNISCATE, OFFSET -> lemniscate(limits, fromVertex);
            case CIRCLE -> circle(limits);
            case SQUARE -> square(SQUARE_SIDE, false, robotLimits);
            case STABILIZE -> throw new IllegalStateException("stabilize has no trajectory");
        };
    }

    /**
     * x = a cos t/(1 + sin&sup2;t), y = a sin t cos t/(1 + sin&sup2;t), started at the crossing point (t = &pi;/2), or
     * at the vertex (a, 0) of the right lobe when {@code fromVertex}.
     * <p>
     * The start matters for the return error. The crossing point is the curve's centroid, and a heading drift growing
     * linearly with distance (what unequal wheel radii cause) rotates a closed run about its centroid: a run started
     * there comes back to its start, and only the error during the lap shows the asymmetry. From the vertex the same
     * drift shows in the return error, but so does the random walk of slip noise, weighted by the distance from the
     * start (up to 2a).
     */
    static Trajectory lemniscate(MotionLimits limits, boolean fromVertex) {
        List<Point2D> pts = new ArrayList<>();
        int n = 96;
        double t0 = fromVertex ? 0 : Math.PI / 2;
        for (int i = 0; i < n; i++) {
            double t = t0 + 2 * Math.PI * i / n;
            double d = 1 + Math.sin(t) * Math.sin(t);
            pts.add(new Point2D(LEMNISCATE_A * Math.cos(t) / d, LEMNISCATE_A * Math.sin(t) * Math.cos(t) / d));
        }
        return SplineTrajectory.plan(pts, true, CRUISE_SPEED, limits);
    }

    static Trajectory circle(MotionLimits limits) {
        List<Point2D> pts = new ArrayList<>();
        int n = 48;
        for (int i = 0; i < n; i++) {
            double t = -Math.PI / 2 + 2 * Math.PI * i / n;
            pts.add(new Point2D(CIRCLE_RADIUS * Math.cos(t), CIRCLE_RADIUS + CIRCLE_RADIUS * Math.sin(t)));
        }
        return SplineTrajectory.plan(pts, true, CRUISE_SPEED, limits);
    }

    /**
     * A square of side {@code side} from the origin heading +x: four legs, each followed by a 90&deg; turn on the
     * spot (the last one restores the start heading), as UMBmark drives it.
     *
     * @param clockwise true to turn right at the corners
     */
    public static Trajectory square(double side, boolean clockwise, MotionLimits robotLimits) {
        MotionLimits limits = robotLimits.withHeadroom(PLANNING_HEADROOM);
        double turnRate = Math.min(1.0, limits.maxAngularSpeed());
        double sign = clockwise ? -1 : 1;
        List<Trajectory> parts = new ArrayList<>();
        double x = 0, y = 0, th = 0;
        for (int leg = 0; leg < 4; leg++) {
            double nx = x + side * Math.cos(th);
            double ny = y + side * Math.sin(th);
            parts.add(SplineTrajectory.plan(List.of(new Point2D(x, y), new Point2D(nx, ny)), false, CRUISE_SPEED, limits));
            parts.add(new TurnInPlaceTrajectory(new Pose2D(nx, ny, th), sign * Math.PI / 2, turnRate,
                    limits.maxAngularAcceleration()));
            x = Math.rint(nx * 1e9) / 1e9;
            y = Math.rint(ny * 1e9) / 1e9;
            th += sign * Math.PI / 2;
        }
        return new TrajectorySequence(parts);
    }

    /** Parses a command-line name. */
    public static Scenario parse(String s) {
        for (Scenario v : values()) {
            if (v.cliName().equals(s)) {
                return v;
            }
        }
        throw new IllegalArgumentException("unknown scenario '" + s + "' (expected lemniscate|circle|square|offset|stabilize)");
    }
}
