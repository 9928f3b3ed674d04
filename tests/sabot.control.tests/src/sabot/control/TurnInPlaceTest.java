package sabot.control;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;
import org.junit.jupiter.api.Test;

import sabot.model.geometry.Twist2D;

/** The turn in place: near the bang-bang time, no overshoot, through the smoother and one period of wheel lag. */
class TurnInPlaceTest {

    private static final MotionLimits LIMITS = new MotionLimits(0.5, 0.5, 2.0, 0.3, 1.2, 0.4);
    private static final double PERIOD = 0.02;

    @ParameterizedTest
    @ValueSource(doubles = { 0.2, 0.43, 1.16, -1.16, 3.0 })
    void turnEndsOnTheTargetNearTheBangBangTime(double angle) {
        TurnInPlace turn = new TurnInPlace(1.6, 0.8 * LIMITS.maxAngularAcceleration(), 5);
        VelocitySmoother smoother = new VelocitySmoother(LIMITS, 1.0);
        double heading = 0, appliedRate = 0, maxBeyond = 0;
        double t = 0;
        while (t < 10) {
            double error = angle - heading;
            if (Math.abs(error) < 0.08 && Math.abs(appliedRate) < 0.5) {
                break;
            }
            Twist2D out = smoother.smooth(t, new Twist2D(0, turn.rate(error)));
            heading += appliedRate * PERIOD; // the wheels follow the set-point one period late
            appliedRate = out.angular();
            maxBeyond = Math.max(maxBeyond, Math.signum(angle) * (heading - angle));
            t += PERIOD;
        }
        double ideal = new TurnInPlace(2.0, LIMITS.maxAngularAcceleration(), 5).minimumTime(angle);
        assertTrue(t < ideal + 0.15, "turn of " + angle + " rad took " + t + " s, bang-bang at the full limits " + ideal);
        assertTrue(maxBeyond < 0.02, "overshoot " + maxBeyond + " rad");
    }

    @Test
    void rateFollowsTheBrakingCurveAndTheProportionalZone() {
        TurnInPlace turn = new TurnInPlace(1.6, 2.0, 5);
        assertEquals(1.6, turn.rate(2.0), 1e-12, "full rate far from the target");
        assertEquals(-Math.sqrt(2 * 2.0 * 0.3), turn.rate(-0.3), 1e-12, "braking curve");
        assertEquals(5 * 0.05, turn.rate(0.05), 1e-12, "proportional zone near the target");
        assertEquals(0, turn.rate(Double.NaN));
        assertEquals(2 * Math.sqrt(0.5 / 2.0), turn.minimumTime(0.5), 1e-12, "triangle profile");
        assertEquals(3.0 / 1.6 + 1.6 / 2.0, turn.minimumTime(-3.0), 1e-12, "trapezoid profile");
    }

    @Test
    void badLimitsAreRefused() {
        assertThrows(IllegalArgumentException.class, () -> new TurnInPlace(0, 1, 1));
        assertThrows(IllegalArgumentException.class, () -> new TurnInPlace(1, Double.NaN, 1));
    }
}
