package sabot.control.trajectory;

import java.util.ArrayList;
import java.util.List;

import sabot.model.geometry.Point2D;

/**
 * A planar C&sup2; cubic spline through waypoints, evaluated by arc length s.
 * <p>
 * Construction: each coordinate is a cubic spline in the chord-length parameter u (natural end conditions for an
 * open path, periodic for a closed one; de Boor, <i>A Practical Guide to Splines</i>, ch. IV). The arc length
 * s(u) = &int;|p'(u)|du is tabulated with 5-point Gauss-Legendre quadrature on sub-intervals; evaluation at s finds u
 * by table look-up and Newton steps on s(u) &minus; s = 0. Derivatives with respect to s follow from the chain rule:
 * p_s = p_u/|p_u| (unit tangent), &kappa; = (x_u y_uu &minus; y_u x_uu)/|p_u|&sup3;, p_ss = &kappa;&middot;n with
 * n the left normal.
 * <p>
 * Waypoint hygiene: consecutive duplicates (closer than {@link #DUPLICATE_TOLERANCE}) are dropped, and so is a
 * closing point equal to the first on a closed path. Fewer than two distinct points (three for a closed path), or a
 * non-finite coordinate, is an {@link InvalidPathException}.
 */
public final class ArcLengthSpline {

    /** Waypoints closer than this (metres) are the same waypoint. */
    public static final double DUPLICATE_TOLERANCE = 1e-6;

    private static final int SUBDIVISIONS = 8;
    private static final double[] GL_NODES = { -0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
            0.9061798459386640 };
    private static final double[] GL_WEIGHTS = { 0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
            0.4786286704993665, 0.2369268850561891 };

    private final boolean closed;
    private final double[] knots; // u_i, length segments+1
    private final double[] ax, bx, cx, dx, ay, by, cy, dy; // per segment, in t = u - u_i
    private final double[] tableU;
    private final double[] tableS;
    private final double length;
    private final double maxAbsCurvature;

    /**
     * @param waypoints map-frame points, metres
     * @param closed    true for a loop (the path returns to the first waypoint with continuous tangent and curvature)
     * @throws InvalidPathException when the waypoints cannot define a path
     */
    public ArcLengthSpline(List<Point2D> waypoints, boolean closed) {
        this.closed = closed;
        List<Point2D> pts = clean(waypoints, closed);
        int n = pts.size();
        int segments = closed ? n : n - 1;
        knots = new double[segments + 1];
        for (int i = 0; i < segments; i++) {
            knots[i + 1] = knots[i] + pts.get(i).distanceTo(pts.get((i + 1) % n));
        }
        double[] xs = new double[segments + 1];
        double[] ys = new double[segments + 1];
        for (int i = 0; i <= segments; i++) {
            xs[i] = pts.get(i % n).x();
            ys[i] = pts.get(i % n).y();
        }
        ax = new double[segments];
        bx = new double[segments];
        cx = new double[segments];
        dx = new double[segments];
        ay = new double[segments];
        by = new double[segments];
        cy = new double[segments];
        dy = new double[segments];
        coefficients(xs, closed ? periodicMoments(xs) : naturalMoments(xs), ax, bx, cx, dx);
        coefficients(ys, closed ? periodicMoments(ys) : naturalMoments(ys), ay, by, cy, dy);

        int rows = segments * SUBDIVISIONS + 1;
        tableU = new double[rows];
        tableS = new double[rows];
        double maxK = 0;
        double[] d = new double[4];
        for (int i = 0; i < segments; i++) {
            double h = (knots[i + 1] - knots[i]) / SUBDIVISIONS;
            for (int j = 0; j < SUBDIVISIONS; j++) {
                int row = i * SUBDIVISIONS + j;
                double u0 = knots[i] + j * h;
                tableU[row] = u0;
                tableS[row + 1] = tableS[row] + arcLength(i, u0 - knots[i], u0 + h - knots[i]);
                for (int q = 0; q < 2; q++) {
                    derivatives(i, u0 - knots[i] + q * h / 2, d);
                    double sp = Math.hypot(d[0], d[1]);
                    if (sp > 0) {
                        maxK = Math.max(maxK, Math.abs(d[0] * d[3] - d[1] * d[2]) / (sp * sp * sp));
                    }
                }
            }
        }
        tableU[rows - 1] = knots[segments];
        length = tableS[rows - 1];
        maxAbsCurvature = maxK;
    }

    private static List<Point2D> clean(List<Point2D> waypoints, boolean closed) {
        if (waypoints == null || waypoints.isEmpty()) {
            throw new InvalidPathException("a path needs waypoints, got none");
        }
        List<Point2D> pts = new ArrayList<>();
        for (int i = 0; i < waypoints.size(); i++) {
            Point2D p = waypoints.get(i);
            if (p == null || !p.isFinite()) {
                throw new InvalidPathException("waypoint " + i + " is not finite: " + p);
            }
            if (pts.isEmpty() || pts.get(pts.size() - 1).distanceTo(p) > DUPLICATE_TOLERANCE) {
                pts.add(p);
            }
        }
        if (closed && pts.size() > 1 && pts.get(0).distanceTo(pts.get(pts.size() - 1)) <= DUPLICATE_TOLERANCE) {
            pts.remove(pts.size() - 1);
        }
        int needed = closed ? 3 : 2;
        if (pts.size() < needed) {
            throw new InvalidPathException((closed ? "a closed" : "an open") + " path needs at least " + needed
                    + " distinct waypoints, got " + pts.size());
        }
        return pts;
    }

    /** Second derivatives M_i of the natural spline (M_0 = M_n = 0), by the Thomas algorithm. */
    private double[] naturalMoments(double[] y) {
        int n = y.length - 1;
        double[] m = new double[n + 1];
        if (n < 2) {
            return m;
        }
        int k = n - 1;
        double[] a = new double[k];
        double[] b = new double[k];
        double[] c = new double[k];
        double[] r = new double[k];
        for (int i = 1; i < n; i++) {
            double h0 = knots[i] - knots[i - 1];
            double h1 = knots[i + 1] - knots[i];
            a[i - 1] = h0;
            b[i - 1] = 2 * (h0 + h1);
            c[i - 1] = h1;
            r[i - 1] = 6 * ((y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0);
        }
        double[] x = thomas(a, b, c, r);
        System.arraycopy(x, 0, m, 1, k);
        return m;
    }

    /** Second derivatives of the periodic spline (M_0 = M_n), cyclic tridiagonal by Sherman-Morrison. */
    private double[] periodicMoments(double[] y) {
        int n = y.length - 1; // segments = distinct points
        double[] a = new double[n];
        double[] b = new double[n];
        double[] c = new double[n];
        double[] r = new double[n];
        for (int i = 0; i < n; i++) {
            double h0 = i == 0 ? knots[n] - knots[n - 1] : knots[i] - knots[i - 1];
            double h1 = knots[i + 1] - knots[i];
            double yPrev = i == 0 ? y[n - 1] : y[i - 1];
            a[i] = h0;
            b[i] = 2 * (h0 + h1);
            c[i] = h1;
            r[i] = 6 * ((y[i + 1] - y[i]) / h1 - (y[i] - yPrev) / h0);
        }
        // Cyclic system: corner terms a[0] (row 0, col n-1) and c[n-1] (row n-1, col 0).
        double gamma = -b[0];
        double[] bb = b.clone();
        bb[0] = b[0] - gamma;
        bb[n - 1] = b[n - 1] - a[0] * c[n - 1] / gamma;
        double[] x = thomas(a, bb, c, r);
        double[] u = new double[n];
        u[0] = gamma;
        u[n - 1] = c[n - 1];
        double[] z = thomas(a, bb, c, u);
        double fact = (x[0] + a[0] * x[n - 1] / gamma) / (1 + z[0] + a[0] * z[n - 1] / gamma);
        double[] m = new double[n + 1];
        for (int i = 0; i < n; i++) {
            m[i] = x[i] - fact * z[i];
        }
        m[n] = m[0];
        return m;
    }

    /** Solves a tridiagonal system; a[0] and c[last] are ignored. */
    private static double[] thomas(double[] a, double[] b, double[] c, double[] r) {
        int n = b.length;
        double[] cp = new double[n];
        double[] x = new double[n];
        double beta = b[0];
        x[0] = r[0] / beta;
        for (int i = 1; i < n; i++) {
            cp[i] = c[i - 1] / beta;
            beta = b[i] - a[i] * cp[i];
            x[i] = (r[i] - a[i] * x[i - 1]) / beta;
        }
        for (int i = n - 2; i >= 0; i--) {
            x[i] -= cp[i + 1] * x[i + 1];
        }
        return x;
    }

    private void coefficients(double[] y, double[] m, double[] a, double[] b, double[] c, double[] d) {
        for (int i = 0; i < a.length; i++) {
            double h = knots[i + 1] - knots[i];
            a[i] = y[i];
            b[i] = (y[i + 1] - y[i]) / h - h * (2 * m[i] + m[i + 1]) / 6;
            c[i] = m[i] / 2;
            d[i] = (m[i + 1] - m[i]) / (6 * h);
        }
    }

    /** out = {x_u, y_u, x_uu, y_uu} at local parameter t of segment i. */
    private void derivatives(int i, double t, double[] out) {
        out[0] = bx[i] + t * (2 * cx[i] + 3 * dx[i] * t);
        out[1] = by[i] + t * (2 * cy[i] + 3 * dy[i] * t);
        out[2] = 2 * cx[i] + 6 * dx[i] * t;
        out[3] = 2 * cy[i] + 6 * dy[i] * t;
    }

    private double speed(int i, double t) {
        double xu = bx[i] + t * (2 * cx[i] + 3 * dx[i] * t);
        double yu = by[i] + t * (2 * cy[i] + 3 * dy[i] * t);
        return Math.hypot(xu, yu);
    }

    private double arcLength(int i, double t0, double t1) {
        double half = (t1 - t0) / 2;
        double mid = (t0 + t1) / 2;
        double sum = 0;
        for (int k = 0; k < GL_NODES.length; k++) {
            sum += GL_WEIGHTS[k] * speed(i, mid + half * GL_NODES[k]);
        }
        return sum * half;
    }

    private int segmentOf(double u) {
        int lo = 0;
        int hi = knots.length - 2;
        while (lo < hi) {
            int mid = (lo + hi + 1) >>> 1;
            if (knots[mid] <= u) {
                lo = mid;
            } else {
                hi = mid - 1;
            }
        }
        return lo;
    }

    /**
     * Evaluates the path at arc length {@code s} (clamped to [0, length]; wrapped for a closed path).
     *
     * @param s   metres along the path
     * @param out receives {x, y, x_s, y_s, x_ss, y_ss, &kappa;}: position (m), unit tangent, second derivative
     *            (1/m) and signed curvature (1/m, positive to the left)
     */
    public void evaluate(double s, double[] out) {
        if (!Double.isFinite(s)) {
            throw new IllegalArgumentException("arc length must be finite, was " + s);
        }
        if (closed) {
            s = s - length * Math.floor(s / length);
        }
        s = Math.max(0, Math.min(length, s));
        int lo = 0;
        int hi = tableS.length - 2;
        while (lo < hi) {
            int mid = (lo + hi + 1) >>> 1;
            if (tableS[mid] <= s) {
                lo = mid;
            } else {
                hi = mid - 1;
            }
        }
        double s0 = tableS[lo];
        double u0 = tableU[lo];
        double u1 = tableU[lo + 1];
        double ds = tableS[lo + 1] - s0;
        int seg = segmentOf(Math.min(u0, knots[knots.length - 1]));
        double base = knots[seg];
        double u = ds > 0 ? u0 + (u1 - u0) * (s - s0) / ds : u0;
        for (int it = 0; it < 4; it++) {
            double sp = speed(seg, u - base);
            if (!(sp > 1e-12)) {
                break;
            }
            double f = arcLength(seg, u0 - base, u - base) - (s - s0);
            double step = f / sp;
            u = Math.max(u0, Math.min(u1, u - step));
            if (Math.abs(step) < 1e-13) {
                break;
            }
        }
        double t = u - base;
        double[] d = new double[4];
        derivatives(seg, t, d);
        out[0] = ax[seg] + t * (bx[seg] + t * (cx[seg] + t * dx[seg]));
        out[1] = ay[seg] + t * (by[seg] + t * (cy[seg] + t * dy[seg]));
        double sp = Math.hypot(d[0], d[1]);
        double tx = d[0] / sp;
        double ty = d[1] / sp;
        double kappa = (d[0] * d[3] - d[1] * d[2]) / (sp * sp * sp);
        out[2] = tx;
        out[3] = ty;
        out[4] = -kappa * ty;
        out[5] = kappa * tx;
        out[6] = kappa;
    }

    /** @return the path's length in metres */
    public double length() {
        return length;
    }

    /** @return true when the path is a loop */
    public boolean isClosed() {
        return closed;
    }

    /** @return the largest |&kappa;| found on the evaluation grid, 1/m */
    public double maxAbsCurvature() {
        return maxAbsCurvature;
    }

    /** @return the point at arc length {@code s} */
    public Point2D pointAt(double s) {
        double[] out = new double[7];
        evaluate(s, out);
        return new Point2D(out[0], out[1]);
    }
}
