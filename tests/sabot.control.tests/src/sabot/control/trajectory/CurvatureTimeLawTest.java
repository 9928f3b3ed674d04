package sabot.control.trajectory;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;

import org.junit.jupiter.api.Test;

import sabot.control.MotionLimits;
import sabot.model.geometry.Point2D;
import sabot.model.path.TrajectorySample;

class CurvatureTimeLawTest {

    private static final MotionLimits LIMITS = new MotionLimits(0.5, 0.5, 2.0, 0.3, 1.2, 0.4);

    /** A straight run, a quarter turn of about 0.6 m radius, a straight run. */
    private static final List<Point2D> L_PATH = List.of(new Point2D(0, 0), new Point2D(2, 0), new Point2D(2.45, 0.2),
            new Point2D(2.6, 0.6), new Point2D(2.6, 3));

    @Test
    void straightPathIsTheTrapezoid() {
        ArcLengthSpline line = new ArcLengthSpline(List.of(new Point2D(0, 0), new Point2D(4, 0)), false);
        CurvatureTimeLaw law = new CurvatureTimeLaw(line, 0.5, LIMITS, 0.005);
        TrapezoidalTimeLaw trapezoid = new TrapezoidalTimeLaw(4, 0.5, 0.5);
        assertEquals(trapezoid.duration(), law.duration(), 0.01);
        double[] a = new double[3];
        double[] b = new double[3];
        for (double t = 0; t <= law.duration(); t += 0.25) {
            law.evaluate(t, a);
            trapezoid.evaluate(t, b);
            assertEquals(b[0], a[0], 0.01, "s at " + t);
            assertEquals(b[1], a[1], 0.01, "speed at " + t);
        }
    }

    @Test
    void profileSlowsOnlyInTheBendAndKeepsEveryLimit() {
        SplineTrajectory curved = SplineTrajectory.planCurvatureLimited(L_PATH, 0.5, LIMITS);
        SplineTrajectory uniform = SplineTrajectory.plan(L_PATH, false, 0.5, LIMITS);
        assertTrue(curved.duration() < 0.9 * uniform.duration(), curved.duration() + " s against one cruise speed's "
                + uniform.duration() + " s");
        double previous = 0;
        double maxSpeed = 0;
        for (double t = 0; t <= curved.duration(); t += 0.01) {
            TrajectorySample r = curved.sample(t);
            double kappa = r.linearVelocity() > 1e-6 ? r.angularVelocity() / r.linearVelocity() : 0;
            assertTrue(r.linearVelocity() <= LIMITS.maxSpeedForCurvature(kappa) * 1.02 + 1e-9,
                    "too fast for the curvature at " + t + ": " + r);
            assertTrue(Math.abs(r.angularVelocity()) <= LIMITS.maxAngularSpeed() * 1.02, "yaw rate at " + t);
            assertTrue(Math.abs(r.linearVelocity() - previous) <= LIMITS.maxLinearAcceleration() * 0.01 + 1e-6,
                    "acceleration at " + t);
            previous = r.linearVelocity();
            maxSpeed = Math.max(maxSpeed, r.linearVelocity());
        }
        assertEquals(0.5, maxSpeed, 0.01, "the straight runs are driven at the cruise speed");
        assertEquals(0, curved.sample(curved.duration()).linearVelocity(), 1e-12);
        TrajectorySample end = curved.sample(curved.duration());
        assertEquals(2.6, end.x(), 1e-6);
        assertEquals(3.0, end.y(), 1e-6);
    }
}
