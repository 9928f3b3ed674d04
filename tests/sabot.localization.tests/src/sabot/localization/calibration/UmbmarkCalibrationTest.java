package sabot.localization.calibration;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import java.util.ArrayList;
import java.util.List;

import org.junit.jupiter.api.Test;

import sabot.localization.OdometryCalibration;

class UmbmarkCalibrationTest {

    private static final double L = 2.0;
    private static final OdometryCalibration NOMINAL = new OdometryCalibration(0.075, 0.075, 0.40);

    /**
     * Forward model of a square run driven by odometry that believes the nominal geometry, on a robot whose true
     * right/left radii are r(1 +- delta) and whose true track is eb*b: wheels turn equally on legs and oppositely
     * by the nominal amount in turns.
     *
     * @return true end position minus odometry end position (the origin), start frame
     */
    static double[] squareRun(boolean clockwise, double delta, double eb) {
        double b = NOMINAL.trackWidth();
        double x = 0, y = 0, th = 0;
        int n = 20000;
        for (int leg = 0; leg < 4; leg++) {
            double sr = L * (1 + delta) / n;
            double sl = L * (1 - delta) / n;
            for (int i = 0; i < n; i++) {
                double ds = (sr + sl) / 2;
                double dth = (sr - sl) / (eb * b);
                x += ds * Math.cos(th + dth / 2);
                y += ds * Math.sin(th + dth / 2);
                th += dth;
            }
            double turn = (clockwise ? -1 : 1) * Math.PI / 2;
            double arc = turn * b / 2; // nominal wheel travel for the turn, right wheel (+), left (-)
            double srT = arc * (1 + delta);
            double slT = -arc * (1 - delta);
            double ds = (srT + slT) / 2;
            double dth = (srT - slT) / (eb * b);
            x += ds * Math.cos(th + dth / 2);
            y += ds * Math.sin(th + dth / 2);
            th += dth;
        }
        return new double[] { x, y };
    }

    private static List<SquareRunResult> runs(double delta, double eb) {
        List<SquareRunResult> r = new ArrayList<>();
        for (boolean cw : new boolean[] { true, false }) {
            double[] e = squareRun(cw, delta, eb);
            r.add(new SquareRunResult(cw, e[0], e[1]));
        }
        return r;
    }

    @Test
    void recoversUnequalWheelDiameters() {
        double delta = 0.001; // left travels 0.999, right 1.001: the 0.2 % slip bias
        OdometryCalibration c = new UmbmarkCalibration(L).calibrate(runs(delta, 1.0), NOMINAL);
        assertEquals((1 + delta) / (1 - delta), c.diameterRatio(), 2e-5);
        assertEquals(0.40, c.trackWidth(), 4e-4);
        assertEquals(0.075, (c.leftWheelRadius() + c.rightWheelRadius()) / 2, 1e-12);
    }

    @Test
    void recoversTrackError() {
        OdometryCalibration c = new UmbmarkCalibration(L).calibrate(runs(0, 1.01), NOMINAL);
        assertEquals(0.404, c.trackWidth(), 2e-4);
        assertEquals(1.0, c.diameterRatio(), 1e-4);
    }

    @Test
    void recoversBothErrorsTogether() {
        OdometryCalibration c = new UmbmarkCalibration(L).calibrate(runs(-0.002, 0.995), NOMINAL);
        assertEquals((1 - 0.002) / (1 + 0.002), c.diameterRatio(), 5e-5);
        assertEquals(0.40 * 0.995, c.trackWidth(), 3e-4);
    }

    @Test
    void bothDirectionsAreRequired() {
        var e = assertThrows(IllegalArgumentException.class,
                () -> new UmbmarkCalibration(L).calibrate(List.of(new SquareRunResult(true, 0.01, 0.02)), NOMINAL));
        assertEquals(true, e.getMessage().contains("counter-clockwise"));
    }
}
