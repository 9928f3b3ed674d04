package sabot.control;

/**
 * Gains of the PD outer loop of dynamic feedback linearization, one pair per flat output:
 * u1 = x&#776;_d + k_p1 (x_d &minus; x) + k_d1 (x&#775;_d &minus; x&#775;), u2 likewise with k_p2, k_d2
 * (Oriolo, De Luca, Vendittelli, IEEE TCST 10(6), 2002, eq. 20).
 *
 * @param kp1 x proportional gain, 1/s&sup2;
 * @param kd1 x derivative gain, 1/s
 * @param kp2 y proportional gain, 1/s&sup2;
 * @param kd2 y derivative gain, 1/s
 */
public record DflGains(double kp1, double kd1, double kp2, double kd2) {

    public DflGains {
        for (double g : new double[] { kp1, kd1, kp2, kd2 }) {
            if (!(g > 0) || !Double.isFinite(g)) {
                throw new InfeasibleGainsException("DFL gains must be finite and > 0 (Hurwitz s^2 + kd s + kp): kp1="
                        + kp1 + ", kd1=" + kd1 + ", kp2=" + kp2 + ", kd2=" + kd2);
            }
        }
    }

    /** @return gains placing both error dynamics at natural frequency {@code omegaN} (rad/s) and damping {@code zeta} */
    public static DflGains of(double omegaN, double zeta) {
        return new DflGains(omegaN * omegaN, 2 * zeta * omegaN, omegaN * omegaN, 2 * zeta * omegaN);
    }

    /**
     * Checks the point-stabilization conditions k_d1&sup2; &minus; 4k_p1 = k_d2&sup2; &minus; 4k_p2 &gt; 0 and
     * k_d2 &minus; k_d1 &gt; 2&radic;(k_d2&sup2; &minus; 4k_p2). Both error dynamics are then overdamped with the same
     * eigenvalue spread &radic;&Delta;, and every y mode decays faster than every x mode, so the robot reaches the goal
     * moving along the goal's x axis: the heading converges too, and the velocity never vanishes before the goal.
     *
     * @return {@code this}
     * @throws InfeasibleGainsException naming the violated condition
     */
    public DflGains requireStabilizing() {
        double d1 = kd1 * kd1 - 4 * kp1;
        double d2 = kd2 * kd2 - 4 * kp2;
        double scale = Math.max(Math.max(kd1 * kd1, kd2 * kd2), 1e-12);
        if (Math.abs(d1 - d2) > 1e-9 * scale) {
            throw new InfeasibleGainsException(String.format(
                    "point stabilization needs kd1^2 - 4 kp1 = kd2^2 - 4 kp2, got %.6g and %.6g", d1, d2));
        }
        if (!(d1 > 0)) {
            throw new InfeasibleGainsException(String.format(
                    "point stabilization needs kd^2 - 4 kp > 0 (overdamped), got %.6g", d1));
        }
        double spread = Math.sqrt(d2);
        if (!(kd2 - kd1 > 2 * spread)) {
            throw new InfeasibleGainsException(String.format(
                    "point stabilization needs kd2 - kd1 > 2 sqrt(kd2^2 - 4 kp2): %.6g <= %.6g", kd2 - kd1, 2 * spread));
        }
        return this;
    }

    /**
     * @return stabilizing gains with x eigenvalues &minus;c, &minus;2c and y eigenvalues &minus;2.5c, &minus;3.5c
     *         (&radic;&Delta; = c), a one-parameter family that satisfies {@link #requireStabilizing()}
     */
    public static DflGains stabilizing(double c) {
        if (!(c > 0) || !Double.isFinite(c)) {
            throw new InfeasibleGainsException("time scale must be finite and > 0, was " + c);
        }
        return new DflGains(2 * c * c, 3 * c, 8.75 * c * c, 6 * c).requireStabilizing();
    }
}
