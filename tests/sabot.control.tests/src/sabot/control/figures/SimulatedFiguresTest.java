package sabot.control.figures;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

import sabot.motion.sim.ControllerKind;
import sabot.motion.sim.Feedback;
import sabot.motion.sim.Metrics;
import sabot.motion.sim.Scenario;
import sabot.motion.sim.Simulation;
import sabot.motion.sim.SimulationConfig;

/**
 * The figures, reproduced by the deterministic simulation (seed 1; the same runs as
 * {@code ./sabot simulate ... --seed 1}, see docs/MOTION.md). No timing is asserted here.
 */
class SimulatedFiguresTest {

    private static Metrics run(Scenario s, ControllerKind c, Feedback f, double noise, double bias, boolean calibrated) {
        return Simulation.run(SimulationConfig.of(s, c, f).withSlip(noise, bias).withCalibrated(calibrated)).metrics();
    }

    @Test
    void dflTracksLemniscateWithinOneCentimetreUnderTwoPercentSlip() {
        Metrics m = run(Scenario.LEMNISCATE, ControllerKind.DFL, Feedback.TRUTH, 0.02, 0, false);
        assertTrue(m.rmsError() <= 0.01, "rms " + m.rmsError());
        assertTrue(m.maxError() <= 0.03, "max " + m.maxError());
        assertEquals(0, m.limitViolations());
        assertEquals(0, m.nanCommands());
    }

    @Test
    void odometryOnlyReturnsWithinTwoCentimetresUnderOnePercentSlip() {
        Metrics m = run(Scenario.LEMNISCATE, ControllerKind.DFL, Feedback.ODOMETRY, 0.01, 0, false);
        assertTrue(m.returnError() <= 0.02, "return " + m.returnError());
    }

    @Test
    void ekfFeedbackBeatsOdometryFiveTimesUnderWheelAsymmetry() {
        // From the lemniscate's crossing point a drift linear in distance cancels in the return error, so the
        // asymmetry is judged on the largest deviation during the lap (after the first 5 s).
        Metrics odometry = run(Scenario.LEMNISCATE, ControllerKind.DFL, Feedback.ODOMETRY, 0.01, 0.002, false);
        Metrics ekf = run(Scenario.LEMNISCATE, ControllerKind.DFL, Feedback.EKF, 0.01, 0.002, false);
        assertTrue(odometry.maxError() > 0.10, "asymmetry shows in odometry-only: " + odometry.maxError());
        assertTrue(ekf.maxError() <= 0.02, "ekf max " + ekf.maxError());
        assertTrue(ekf.returnError() <= 0.02, "ekf return " + ekf.returnError());
        assertTrue(odometry.maxError() >= 5 * ekf.maxError(),
                "odometry " + odometry.maxError() + " vs ekf " + ekf.maxError());
    }

    @Test
    void umbmarkCalibrationRemovesTheAsymmetryFromOdometry() {
        Metrics raw = run(Scenario.LEMNISCATE, ControllerKind.DFL, Feedback.ODOMETRY, 0.01, 0.002, false);
        Metrics calibrated = run(Scenario.LEMNISCATE, ControllerKind.DFL, Feedback.ODOMETRY, 0.01, 0.002, true);
        assertTrue(calibrated.returnError() <= 0.03, "calibrated odometry return " + calibrated.returnError());
        assertTrue(calibrated.maxError() <= raw.maxError() / 2,
                "calibrated max " + calibrated.maxError() + " vs raw " + raw.maxError());
    }

    @Test
    void dflRecoversFromStartOffsetWithinSixSecondsWithoutBreakingLimits() {
        Metrics m = run(Scenario.OFFSET, ControllerKind.DFL, Feedback.TRUTH, 0, 0, false);
        assertTrue(m.settleTime() <= 6.0, "settle " + m.settleTime());
        assertEquals(0, m.limitViolations());
    }

    @Test
    void dflStabilizesTwentyRandomStartsWithinOneCentimetre() {
        Metrics m = run(Scenario.STABILIZE, ControllerKind.DFL, Feedback.TRUTH, 0, 0, false);
        assertTrue(m.finalError() <= 0.01, "final " + m.finalError());
        assertEquals(0, m.nanCommands());
        assertEquals(0, m.limitViolations());
        assertTrue(m.maxYawRate() <= 2.0 + 1e-9, "no blow-up near xi = 0: " + m.maxYawRate());
    }

    @Test
    void sameSeedGivesIdenticalResults() {
        SimulationConfig c = SimulationConfig.of(Scenario.CIRCLE, ControllerKind.DFL, Feedback.EKF).withSlip(0.01, 0.001)
                .withSeed(42);
        assertEquals(Simulation.run(c).metrics(), Simulation.run(c).metrics());
    }

    @Test
    void robotStopsWhenOdometryStopsReporting() {
        SimulationConfig c = SimulationConfig.of(Scenario.CIRCLE, ControllerKind.DFL, Feedback.EKF).withOdometryDropout(5.0);
        var result = Simulation.run(c);
        var trace = result.trace();
        int tc = sabot.motion.sim.Trace.column("t_s");
        int vc = sabot.motion.sim.Trace.column("v_cmd_mps");
        for (int r = 0; r < trace.size(); r++) {
            // dropout + odometry timeout + time to brake the fastest wheel (<= v_max) at a_max + margin
            if (trace.get(r, tc) > 5.0 + 0.2 + 0.5 / 0.5 + 0.1) {
                assertEquals(0, trace.get(r, vc), 1e-12, "stopped at t=" + trace.get(r, tc));
            }
        }
        assertEquals(0, result.metrics().nanCommands());
    }
}
