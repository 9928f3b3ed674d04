package sabot.control;

/**
 * Gains of the pseudoinverse (kinematic inversion) tracking law.
 *
 * @param kp     position gain, 1/s
 * @param kTheta heading gain, 1/s
 */
public record PseudoinverseGains(double kp, double kTheta) {

    public PseudoinverseGains {
        if (!(kp > 0) || !(kTheta > 0) || !Double.isFinite(kp) || !Double.isFinite(kTheta)) {
            throw new InfeasibleGainsException("pseudoinverse gains must be finite and > 0: kp=" + kp + ", kTheta=" + kTheta);
        }
    }
}
