package sabot.control.trajectory;

import java.util.Arrays;

import sabot.control.MotionLimits;

/**
 * A rest-to-rest speed profile along a path that slows down only where the path bends: at every arc-length step the
 * speed is bounded by the cruise speed and by what the local curvature allows ({@link MotionLimits#maxSpeedForCurvature}:
 * lateral acceleration, yaw rate, outer wheel), then a forward pass bounds the acceleration and a backward pass the
 * deceleration (|s&#776;| &le; a_max), the usual two-pass profile of path-velocity decomposition (Siciliano et al.
 * 2009, &sect;11.5.2; Bobrow et al. 1985). Between two steps the acceleration is constant. Compared with one cruise
 * speed for the whole path ({@link TrapezoidalTimeLaw} at the sharpest curvature's speed), a path that bends once is
 * driven at full speed everywhere else.
 */
public final class CurvatureTimeLaw implements TimeLaw {

    /** Arc-length step of the profile, m: a fraction of the smallest waypoint spacing a planner produces. */
    public static final double DEFAULT_STEP = 0.02;

    private final double distance;
    private final double[] s;
    private final double[] v;
    private final double[] t;

    /**
     * @param path        the path
     * @param cruiseSpeed the largest speed wanted, m/s, &gt; 0
     * @param limits      speed, acceleration and curvature bounds
     * @param step        arc-length step, m, &gt; 0
     */
    public CurvatureTimeLaw(ArcLengthSpline path, double cruiseSpeed, MotionLimits limits, double step) {
        if (!(cruiseSpeed > 0) || !(step > 0) || !Double.isFinite(cruiseSpeed) || !Double.isFinite(step)) {
            throw new IllegalArgumentException("cruise speed and step must be finite and > 0");
        }
        this.distance = path.length();
        int n = Math.max(1, (int) Math.ceil(distance / step));
        double ds = distance / n;
        double a = limits.maxLinearAcceleration();
        s = new double[n + 1];
        v = new double[n + 1];
        t = new double[n + 1];
        double[] p = new double[7];
        for (int i = 0; i <= n; i++) {
            s[i] = i * ds;
            path.evaluate(s[i], p);
            v[i] = Math.min(cruiseSpeed, limits.maxSpeedForCurvature(p[6]));
        }
        v[0] = 0;
        v[n] = 0;
        for (int i = 1; i <= n; i++) {
            v[i] = Math.min(v[i], Math.sqrt(v[i - 1] * v[i - 1] + 2 * a * ds));
        }
        for (int i = n - 1; i >= 0; i--) {
            v[i] = Math.min(v[i], Math.sqrt(v[i + 1] * v[i + 1] + 2 * a * ds));
        }
        for (int i = 1; i <= n; i++) {
            double mean = (v[i - 1] + v[i]) / 2;
            t[i] = t[i - 1] + (mean > 0 ? ds / mean : 0);
        }
    }

    @Override
    public double duration() {
        return t[t.length - 1];
    }

    @Override
    public double distance() {
        return distance;
    }

    /** @return the profile's top speed, m/s */
    public double peakSpeed() {
        return Arrays.stream(v).max().orElse(0);
    }

    @Override
    public void evaluate(double time, double[] out) {
        if (!Double.isFinite(time)) {
            throw new IllegalArgumentException("time must be finite, was " + time);
        }
        if (time <= 0 || duration() == 0) {
            out[0] = time <= 0 ? 0 : distance;
            out[1] = 0;
            out[2] = 0;
            return;
        }
        if (time >= duration()) {
            out[0] = distance;
            out[1] = 0;
            out[2] = 0;
            return;
        }
        int i = Arrays.binarySearch(t, time);
        int k = i >= 0 ? Math.min(i, t.length - 2) : -i - 2; // segment [k, k + 1] holds the time
        double dt = t[k + 1] - t[k];
        double acc = dt > 0 ? (v[k + 1] - v[k]) / dt : 0;
        double tau = time - t[k];
        out[0] = s[k] + v[k] * tau + acc * tau * tau / 2;
        out[1] = v[k] + acc * tau;
        out[2] = acc;
    }
}
