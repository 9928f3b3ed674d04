package sabot.onboard.internal.pidstep;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.ArrayList;
import java.util.List;
import java.util.function.DoubleUnaryOperator;

import org.junit.jupiter.api.Test;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.payload.PayloadException;
import sabot.pidstep.StepFigures;
import sabot.pidstep.StepSample;
import sabot.pidstep.controlml.StepTest;

/**
 * The step-response figures against responses whose figures are known in closed form (first- and second-order
 * systems), and the {@code cm.pid.step} codec's schema. No OSGi service, no robot.
 */
class StepFiguresTest {

    private static final double DT = 1e-5;

    private static List<StepSample> sampled(double step, double until, DoubleUnaryOperator unitResponse) {
        List<StepSample> s = new ArrayList<>();
        for (int i = 0; i * DT <= until; i++) {
            s.add(new StepSample(i * DT, step, step * unitResponse.applyAsDouble(i * DT)));
        }
        return s;
    }

    @Test
    void firstOrderResponseHasTheTextbookFigures() {
        double tau = 0.01;
        StepFigures f = StepFigures.of(sampled(0.004, 0.1, t -> 1 - Math.exp(-t / tau)));
        assertEquals(tau * Math.log(9), f.riseTime(), 2 * DT, "10-90 % rise = tau ln 9");
        assertEquals(0, f.overshoot(), 1e-12);
        assertEquals(tau * Math.log(50), f.settlingTime(), 2 * DT, "2 % settling = tau ln 50");
        assertEquals(0.004 * Math.exp(-0.1 / tau), f.finalError(), 1e-9);
    }

    @Test
    void underdampedSecondOrderOvershootIsExact() {
        double zeta = 0.3;
        double wn = 400;
        double wd = wn * Math.sqrt(1 - zeta * zeta);
        double phi = Math.acos(zeta);
        DoubleUnaryOperator y = t -> 1 - Math.exp(-zeta * wn * t) / Math.sqrt(1 - zeta * zeta) * Math.sin(wd * t
                + phi);
        StepFigures f = StepFigures.of(sampled(0.002, 0.2, y));
        double expected = 100 * Math.exp(-zeta * Math.PI / Math.sqrt(1 - zeta * zeta));
        assertEquals(expected, f.overshoot(), 0.01, "Mp = exp(-zeta pi / sqrt(1 - zeta^2))");
        // the 2 % envelope bound 4 / (zeta wn) = 33 ms; the response itself enters the band for good a little earlier
        assertTrue(f.settlingTime() > 0.02 && f.settlingTime() <= 4 / (zeta * wn), "settling " + f.settlingTime());
    }

    @Test
    void aNegativeStepHasTheFiguresOfItsMirrorImage() {
        DoubleUnaryOperator y = t -> 1 - Math.exp(-t / 0.005) * Math.cos(300 * t);
        StepFigures up = StepFigures.of(sampled(0.003, 0.1, y));
        StepFigures down = StepFigures.of(sampled(-0.003, 0.1, y));
        assertEquals(up.riseTime(), down.riseTime(), 1e-12);
        assertEquals(up.overshoot(), down.overshoot(), 1e-9);
        assertEquals(up.settlingTime(), down.settlingTime(), 1e-12);
        assertEquals(-up.finalError(), down.finalError(), 1e-12);
    }

    @Test
    void figuresTheSamplesDoNotShowAreNaN() {
        StepFigures f = StepFigures.of(sampled(0.004, 0.01, t -> 0.8 * (1 - Math.exp(-t / 0.001))));
        assertTrue(Double.isNaN(f.riseTime()), "never reaches 90 %");
        assertTrue(Double.isNaN(f.settlingTime()), "ends outside the band");
        assertEquals(0, f.overshoot());
    }

    @Test
    void badSampleSetsAreRefusedWithTheirReason() {
        assertEquals("a step response needs at least 2 samples, has 1", assertThrows(IllegalArgumentException.class,
                () -> StepFigures.of(List.of(new StepSample(0, 1, 0)))).getMessage());
        assertEquals("the step (the last set-point) is 0.0", assertThrows(IllegalArgumentException.class,
                () -> StepFigures.of(List.of(new StepSample(0, 0, 0), new StepSample(1, 0, 0)))).getMessage());
        assertEquals("sample times decrease at t = 0.5 s", assertThrows(IllegalArgumentException.class,
                () -> StepFigures.of(List.of(new StepSample(1, 1, 0), new StepSample(0.5, 1, 1)))).getMessage());
        assertEquals("settling band 1.0 is not in (0, 1)", assertThrows(IllegalArgumentException.class,
                () -> StepFigures.of(sampled(1, 0.001, t -> 1), 1.0)).getMessage());
    }

    @Test
    void theStepTestPayloadRoundTripsAndItsSchemaRefusesBadValues() throws Exception {
        StepTest answer = new StepTest(1, 0.003, sampled(0.003, 0.0001, t -> t * 10));
        assertEquals(answer, StepTest.CODEC.decode(StepTest.CODEC.encode(answer)));
        assertEquals(StepTest.request(0, -0.002), StepTest.CODEC.decode(StepTest.CODEC.encode(StepTest.request(0,
                -0.002))));
        assertRefused(ControlMlCondition.INVALID_VALUE, new StepTest(0, 0, List.of()), "step must not be 0 m");
        assertRefused(ControlMlCondition.INVALID_VALUE, new StepTest(0, 0.2, List.of()), "step");
        assertRefused(ControlMlCondition.INVALID_VALUE, new StepTest(16, 0.001, List.of()), "motor");
        assertRefused(ControlMlCondition.INVALID_VALUE, new StepTest(0, 0.001, List.of(new StepSample(0.1, 0, 0),
                new StepSample(0.05, 0, 0))), "sample times must start at >= 0 s and not decrease");
    }

    private static void assertRefused(ControlMlCondition condition, StepTest value, String text) {
        PayloadException e = assertThrows(PayloadException.class, () -> StepTest.CODEC.decode(StepTest.CODEC.encode(
                value)));
        assertEquals(condition, e.error().cmCondition());
        assertTrue(e.getMessage().contains(text), e.getMessage());
    }
}
