package sabot.control.trajectory;

import java.util.List;

import sabot.control.MotionLimits;
import sabot.model.geometry.Point2D;
import sabot.model.path.Trajectory;
import sabot.model.path.TrajectorySample;

/**
 * A path and a time law combined: s = s(t), then v(t) = s&#775;, &omega;(t) = &kappa;(s)&middot;s&#775;,
 * p&#775; = p_s s&#775;, p&#776; = p_ss s&#775;&sup2; + p_s s&#776; (Siciliano et al. 2009, &sect;11.5.1-11.5.2).
 */
public final class SplineTrajectory implements Trajectory {

    private final ArcLengthSpline path;
    private final TimeLaw law;

    public SplineTrajectory(ArcLengthSpline path, TimeLaw law) {
        if (Math.abs(law.distance() - path.length()) > 1e-9 * Math.max(1, path.length())) {
            throw new IllegalArgumentException("time law covers " + law.distance() + " m, path is " + path.length() + " m");
        }
        this.path = path;
        this.law = law;
    }

    /**
     * Plans a rest-to-rest trajectory through waypoints with a trapezoidal law whose cruise speed is the smallest of
     * {@code cruiseSpeed}, v_max and the speed the path's sharpest curvature allows (lateral acceleration, yaw rate
     * and outer-wheel limits of {@link MotionLimits#maxSpeedForCurvature}).
     *
     * @param waypoints   map-frame points
     * @param closed      true for a loop back to the first waypoint
     * @param cruiseSpeed requested speed, m/s, &gt; 0
     * @param limits      the robot's envelope
     * @throws InvalidPathException when the waypoints do not define a path
     */
    public static SplineTrajectory plan(List<Point2D> waypoints, boolean closed, double cruiseSpeed, MotionLimits limits) {
        ArcLengthSpline spline = new ArcLengthSpline(waypoints, closed);
        double v = Math.min(cruiseSpeed, limits.maxSpeedForCurvature(spline.maxAbsCurvature()));
        // Tangential and centripetal demands add up: keep a_max for the ramps only where the curvature allows.
        return new SplineTrajectory(spline, new TrapezoidalTimeLaw(spline.length(), v, limits.maxLinearAcceleration()));
    }

    /**
     * Plans a rest-to-rest trajectory through waypoints that slows down only where the path bends
     * ({@link CurvatureTimeLaw}), at most at {@code cruiseSpeed}.
     *
     * @throws InvalidPathException when the waypoints do not define a path
     */
    public static SplineTrajectory planCurvatureLimited(List<Point2D> waypoints, double cruiseSpeed,
            MotionLimits limits) {
        ArcLengthSpline spline = new ArcLengthSpline(waypoints, false);
        return new SplineTrajectory(spline, new CurvatureTimeLaw(spline, cruiseSpeed, limits,
                CurvatureTimeLaw.DEFAULT_STEP));
    }

    @Override
    public double duration() {
        return law.duration();
    }

    @Override
    public double length() {
        return path.length();
    }

    /** @return the geometric path */
    public ArcLengthSpline path() {
        return path;
    }

    @Override
    public TrajectorySample sample(double time) {
        if (!Double.isFinite(time)) {
            throw new IllegalArgumentException("time must be finite, was " + time);
        }
        double[] sl = new double[3];
        law.evaluate(time, sl);
        double[] p = new double[7];
        path.evaluate(sl[0], p);
        double sd = sl[1];
        double sdd = sl[2];
        double theta = Math.atan2(p[3], p[2]);
        return new TrajectorySample(time, p[0], p[1], theta, sd, p[6] * sd, p[2] * sd, p[3] * sd,
                p[4] * sd * sd + p[2] * sdd, p[5] * sd * sd + p[3] * sdd);
    }
}
