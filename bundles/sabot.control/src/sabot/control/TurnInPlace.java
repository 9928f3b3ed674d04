package sabot.control;

/**
 * The yaw rate of a turn in place onto a heading, as fast as the limits allow: full rate, then the braking curve
 * &omega; = &radic;(2&alpha;|e|) on which the robot comes to rest exactly on the target while decelerating at &alpha;,
 * then, close to the target, a proportional zone &omega; = k&middot;e (the braking curve's gain grows without bound
 * as e &rarr; 0, more than a sampled loop and the wheels' speed loops can follow). Nav2's rotation shim turns the
 * same way before a path is followed.
 * <p>
 * The acceleration towards the rate is the caller's: run the output through {@link VelocitySmoother}, whose
 * angular acceleration bound should be at least {@code maxAcceleration}.
 */
public final class TurnInPlace {

    private final double maxRate;
    private final double maxAcceleration;
    private final double gain;

    /**
     * @param maxRate         top yaw rate of the turn, rad/s
     * @param maxAcceleration deceleration the braking curve assumes, rad/s&sup2; (below the robot's bound, so that a
     *                        late period does not overshoot)
     * @param gain            gain k of the proportional zone, 1/s
     */
    public TurnInPlace(double maxRate, double maxAcceleration, double gain) {
        for (double v : new double[] { maxRate, maxAcceleration, gain }) {
            if (!(v > 0) || !Double.isFinite(v)) {
                throw new IllegalArgumentException("turn rate, acceleration and gain must be finite and > 0, were "
                        + maxRate + ", " + maxAcceleration + ", " + gain);
            }
        }
        this.maxRate = maxRate;
        this.maxAcceleration = maxAcceleration;
        this.gain = gain;
    }

    /**
     * @param error target heading minus current heading, rad, wrapped into (&minus;&pi;, &pi;]
     * @return yaw rate, rad/s, with the sign of {@code error}; 0 for a NaN error
     */
    public double rate(double error) {
        if (Double.isNaN(error)) {
            return 0;
        }
        double e = Math.abs(error);
        double rate = Math.min(maxRate, Math.min(Math.sqrt(2 * maxAcceleration * e), gain * e));
        return Math.copySign(rate, error);
    }

    /** @return the least time (s) a turn through {@code angle} takes from rest to rest at these limits: bang-bang */
    public double minimumTime(double angle) {
        double a = Math.abs(angle);
        double full = maxRate * maxRate / maxAcceleration; // angle turned accelerating to maxRate and braking again
        return a <= full ? 2 * Math.sqrt(a / maxAcceleration) : a / maxRate + maxRate / maxAcceleration;
    }
}
