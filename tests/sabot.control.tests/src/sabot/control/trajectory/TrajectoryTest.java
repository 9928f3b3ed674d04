package sabot.control.trajectory;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.ArrayList;
import java.util.List;

import org.junit.jupiter.api.Test;

import sabot.control.MotionLimits;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.path.TrajectorySample;

class TrajectoryTest {

    private static final MotionLimits LIMITS = new MotionLimits(0.5, 0.5, 2.0, 0.3, 1.2, 0.4);

    private static List<Point2D> circle(double radius, int n) {
        List<Point2D> pts = new ArrayList<>();
        for (int i = 0; i < n; i++) {
            double a = 2 * Math.PI * i / n;
            pts.add(new Point2D(radius * Math.cos(a), radius * Math.sin(a)));
        }
        return pts;
    }

    @Test
    void straightSplineHasChordLengthAndUnitTangent() {
        ArcLengthSpline s = new ArcLengthSpline(List.of(new Point2D(0, 0), new Point2D(3, 4)), false);
        assertEquals(5, s.length(), 1e-12);
        double[] out = new double[7];
        s.evaluate(2.5, out);
        assertEquals(1.5, out[0], 1e-12);
        assertEquals(2.0, out[1], 1e-12);
        assertEquals(0.6, out[2], 1e-12);
        assertEquals(0.8, out[3], 1e-12);
        assertEquals(0, out[6], 1e-12);
    }

    @Test
    void closedSplineThroughCirclePointsHasTheCirclesLengthAndCurvature() {
        ArcLengthSpline s = new ArcLengthSpline(circle(1.5, 48), true);
        assertEquals(2 * Math.PI * 1.5, s.length(), 1e-4);
        double[] out = new double[7];
        for (double a = 0; a < s.length(); a += 0.37) {
            s.evaluate(a, out);
            assertEquals(1 / 1.5, out[6], 2e-3, "curvature at s=" + a);
            assertEquals(1.0, Math.hypot(out[2], out[3]), 1e-12, "unit tangent");
        }
    }

    @Test
    void evaluationIsParameterisedByArcLength() {
        List<Point2D> pts = List.of(new Point2D(0, 0), new Point2D(1, 0.5), new Point2D(2, -0.3), new Point2D(3.5, 1));
        ArcLengthSpline s = new ArcLengthSpline(pts, false);
        double[] a = new double[7];
        double[] b = new double[7];
        double ds = 1e-4;
        for (double u = 0.1; u < s.length() - 0.1; u += 0.2) {
            s.evaluate(u, a);
            s.evaluate(u + ds, b);
            assertEquals(ds, Math.hypot(b[0] - a[0], b[1] - a[1]), 1e-9, "chord = arc for tiny steps at " + u);
            assertEquals(a[4], (b[2] - a[2]) / ds, 1e-3, "second derivative is d(tangent)/ds");
        }
    }

    @Test
    void closedSplineIsContinuousAcrossItsSeam() {
        ArcLengthSpline s = new ArcLengthSpline(circle(1, 12), true);
        double[] end = new double[7];
        double[] start = new double[7];
        s.evaluate(s.length() - 1e-9, end);
        s.evaluate(0, start);
        for (int i = 0; i < 7; i++) {
            assertEquals(start[i], end[i], 1e-6, "component " + i);
        }
    }

    @Test
    void duplicateWaypointsAreDropped() {
        ArcLengthSpline s = new ArcLengthSpline(
                List.of(new Point2D(0, 0), new Point2D(0, 0), new Point2D(1, 0), new Point2D(1, 0)), false);
        assertEquals(1, s.length(), 1e-12);
    }

    @Test
    void emptyOnePointOrAllDuplicatePathsAreRejected() {
        assertThrows(InvalidPathException.class, () -> new ArcLengthSpline(List.of(), false));
        assertThrows(InvalidPathException.class, () -> new ArcLengthSpline(List.of(new Point2D(1, 1)), false));
        var e = assertThrows(InvalidPathException.class,
                () -> new ArcLengthSpline(List.of(new Point2D(1, 1), new Point2D(1, 1)), false));
        assertTrue(e.getMessage().contains("at least 2 distinct"), e.getMessage());
        assertThrows(InvalidPathException.class,
                () -> new ArcLengthSpline(List.of(new Point2D(0, 0), new Point2D(1, 0)), true));
    }

    @Test
    void nonFiniteWaypointsAreRejected() {
        var e = assertThrows(InvalidPathException.class,
                () -> new ArcLengthSpline(List.of(new Point2D(0, 0), new Point2D(Double.NaN, 1)), false));
        assertTrue(e.getMessage().contains("waypoint 1"), e.getMessage());
    }

    @Test
    void trapezoidalLawRespectsSpeedAndAccelerationAndEndsAtTheDistance() {
        TrapezoidalTimeLaw law = new TrapezoidalTimeLaw(3.0, 0.4, 0.5);
        double[] out = new double[3];
        double prevV = 0;
        for (double t = 0; t <= law.duration(); t += 0.001) {
            law.evaluate(t, out);
            assertTrue(out[1] <= 0.4 + 1e-12 && out[1] >= 0);
            assertTrue(Math.abs(out[1] - prevV) <= 0.5 * 0.001 + 1e-9);
            prevV = out[1];
        }
        law.evaluate(law.duration(), out);
        assertEquals(3.0, out[0], 1e-12);
        assertEquals(3.0 / 0.4 + 0.4 / 0.5, law.duration(), 1e-12);
    }

    @Test
    void shortDistanceGivesATriangularProfile() {
        TrapezoidalTimeLaw law = new TrapezoidalTimeLaw(0.02, 0.4, 0.5);
        assertEquals(Math.sqrt(0.5 * 0.02), law.peakSpeed(), 1e-12);
        double[] out = new double[3];
        law.evaluate(law.duration() / 2, out);
        assertEquals(0.01, out[0], 1e-12);
    }

    @Test
    void commandsAreRebuiltFromGeometryAndTiming() {
        SplineTrajectory tr = SplineTrajectory.plan(circle(1.0, 48), true, 0.3, LIMITS);
        for (double t = 0; t < tr.duration(); t += 0.5) {
            TrajectorySample s = tr.sample(t);
            double v = s.linearVelocity();
            assertEquals(v * Math.cos(s.theta()), s.xDot(), 1e-12);
            assertEquals(v * Math.sin(s.theta()), s.yDot(), 1e-12);
            if (v > 0.05) {
                // omega = kappa * sdot, and omega = (xdot*yddot - ydot*xddot)/v^2 for the flat output
                assertEquals(s.angularVelocity(), (s.xDot() * s.yDdot() - s.yDot() * s.xDdot()) / (v * v), 1e-9);
                assertEquals(1.0, s.angularVelocity() / v, 3e-3);
            }
        }
    }

    @Test
    void plannedSpeedRespectsTheLateralAccelerationLimit() {
        SplineTrajectory tight = SplineTrajectory.plan(circle(0.2, 32), true, 0.5, LIMITS);
        double vmax = 0;
        for (double t = 0; t < tight.duration(); t += 0.05) {
            TrajectorySample s = tight.sample(t);
            vmax = Math.max(vmax, s.linearVelocity());
            assertTrue(Math.abs(s.linearVelocity() * s.angularVelocity()) <= 0.3 * 1.01, "lateral at t=" + t);
        }
        assertTrue(vmax < 0.5 && vmax > 0.2, "slowed down by curvature: " + vmax);
    }

    @Test
    void referenceHoldsStillOutsideItsInterval() {
        SplineTrajectory tr = SplineTrajectory.plan(List.of(new Point2D(0, 0), new Point2D(1, 0)), false, 0.3, LIMITS);
        assertEquals(0, tr.sample(-5).linearVelocity());
        assertEquals(1, tr.sample(tr.duration() + 5).x(), 1e-12);
        assertThrows(IllegalArgumentException.class, () -> tr.sample(Double.NaN));
    }

    @Test
    void turnInPlaceKeepsThePositionAndReachesTheAngle() {
        TurnInPlaceTrajectory turn = new TurnInPlaceTrajectory(new Pose2D(1, 2, 0.5), -Math.PI / 2, 1.0, 2.0);
        TrajectorySample end = turn.sample(turn.duration());
        assertEquals(0.5 - Math.PI / 2, end.theta(), 1e-12);
        assertEquals(1, end.x());
        assertEquals(0, turn.sample(turn.duration() / 2).linearVelocity());
        assertEquals(-1.0, turn.sample(turn.duration() / 2).angularVelocity(), 1e-12);
    }

    @Test
    void sequencePlaysPartsOneAfterTheOther() {
        var a = SplineTrajectory.plan(List.of(new Point2D(0, 0), new Point2D(1, 0)), false, 0.3, LIMITS);
        var b = new TurnInPlaceTrajectory(new Pose2D(1, 0, 0), Math.PI / 2, 1.0, 2.0);
        TrajectorySequence seq = new TrajectorySequence(List.of(a, b));
        assertEquals(a.duration() + b.duration(), seq.duration(), 1e-12);
        TrajectorySample mid = seq.sample(a.duration() + b.duration() / 2);
        assertEquals(Math.PI / 4, mid.theta(), 1e-9);
        assertEquals(a.duration() + b.duration() / 2, mid.time(), 1e-12);
        assertThrows(IllegalArgumentException.class, () -> new TrajectorySequence(List.of()));
    }
}
