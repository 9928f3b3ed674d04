package sabot.localization.calibration;

import java.util.List;

import sabot.localization.OdometryCalibration;

/**
 * Estimates the wheel-diameter ratio E_d = D_R/D_L and the track error E_b = b_actual/b_nominal from clockwise and
 * counter-clockwise square runs, UMBmark style (Borenstein and Feng 1996, eqs. 8-17), and returns the corrected
 * odometry geometry.
 * <p>
 * Derivation in Sabot's frame (start at the origin heading +x, counter-clockwise positive). A heading error e made
 * at point P rotates the rest of a closed run about P and moves its end by e&middot;R<sub>90</sub>(&minus;P). Unequal
 * wheels bend every straight leg of length L into an arc turning by &beta; (half of it counted at each end of the
 * leg); a wrong track makes every 90&deg; turn off by &tau; = (&pi;/2)(1/E_b &minus; 1) in the turn's direction.
 * Summing over the corners (L,0), (L,&plusmn;L), (0,&plusmn;L):
 * <pre>
 *   counter-clockwise: &epsilon; = (&beta; + &tau;)(2L, &minus;2L)      clockwise: &epsilon; = (&beta; &minus; &tau;)(&minus;2L, &minus;2L)
 * </pre>
 * so, using both coordinates of the centres of gravity of the runs,
 * &beta; = [(x_ccw &minus; x_cw) &minus; (y_cw + y_ccw)]/(8L) and &tau; = [(x_cw + x_ccw) + (y_cw &minus; y_ccw)]/(8L).
 * Then, as in UMBmark, R = (L/2)/sin(&beta;/2), E_d = (R + b/2)/(R &minus; b/2), and E_b = (&pi;/2)/(&pi;/2 + &tau;).
 * The correction keeps the mean wheel radius: r_L = 2r/(E_d + 1), r_R = 2r/(1/E_d + 1), b = E_b&middot;b_nominal.
 */
public final class UmbmarkCalibration {

    private final double sideLength;

    /** @param sideLength the square's side L, metres */
    public UmbmarkCalibration(double sideLength) {
        if (!(sideLength > 0) || !Double.isFinite(sideLength)) {
            throw new IllegalArgumentException("square side must be finite and > 0, was " + sideLength);
        }
        this.sideLength = sideLength;
    }

    /**
     * @param runs    at least one clockwise and one counter-clockwise run (UMBmark uses five of each)
     * @param current the geometry the odometry used during the runs
     * @return the corrected geometry
     * @throws IllegalArgumentException when a direction is missing or the errors imply an impossible geometry
     */
    public OdometryCalibration calibrate(List<SquareRunResult> runs, OdometryCalibration current) {
        double xcw = 0, ycw = 0, xccw = 0, yccw = 0;
        int ncw = 0, nccw = 0;
        for (SquareRunResult r : runs) {
            if (r.clockwise()) {
                xcw += r.errorX();
                ycw += r.errorY();
                ncw++;
            } else {
                xccw += r.errorX();
                yccw += r.errorY();
                nccw++;
            }
        }
        if (ncw == 0 || nccw == 0) {
            throw new IllegalArgumentException("UMBmark needs clockwise and counter-clockwise runs, got " + ncw
                    + " clockwise and " + nccw + " counter-clockwise");
        }
        xcw /= ncw;
        ycw /= ncw;
        xccw /= nccw;
        yccw /= nccw;
        double l = sideLength;
        double beta = ((xccw - xcw) - (ycw + yccw)) / (8 * l);
        double tau = ((xcw + xccw) + (ycw - yccw)) / (8 * l);
        double b = current.trackWidth();
        double ed;
        if (Math.abs(beta) < 1e-12) {
            ed = 1;
        } else {
            double radius = (l / 2) / Math.sin(beta / 2);
            ed = (radius + b / 2) / (radius - b / 2);
        }
        double eb = (Math.PI / 2) / (Math.PI / 2 + tau);
        if (!(ed > 0) || !(eb > 0) || !Double.isFinite(ed) || !Double.isFinite(eb)) {
            throw new IllegalArgumentException("square-run errors imply an impossible geometry: E_d=" + ed + ", E_b=" + eb);
        }
        // The runs measured the error of the geometry in use: compose the correction with it.
        double ratio = current.diameterRatio() * ed;
        double mean = (current.leftWheelRadius() + current.rightWheelRadius()) / 2;
        return new OdometryCalibration(2 * mean / (ratio + 1), 2 * mean / (1 / ratio + 1), b * eb);
    }
}
