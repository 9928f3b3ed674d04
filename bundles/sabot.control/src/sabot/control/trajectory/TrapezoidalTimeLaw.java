package sabot.control.trajectory;

/**
 * Trapezoidal speed profile from rest to rest: accelerate at {@code a}, cruise at {@code vCruise}, decelerate at
 * {@code a}; triangular when the distance is too short to reach the cruise speed (peak &radic;(a&middot;L)).
 * The acceleration is discontinuous (bang-coast-bang), which the controllers' feedforward follows exactly.
 */
public final class TrapezoidalTimeLaw implements TimeLaw {

    private final double distance;
    private final double a;
    private final double vPeak;
    private final double tAccel;
    private final double tCruise;
    private final double duration;

    /**
     * @param distance metres, &ge; 0 (0 gives an empty law of zero duration)
     * @param vCruise  m/s, &gt; 0
     * @param a        m/s&sup2;, &gt; 0
     */
    public TrapezoidalTimeLaw(double distance, double vCruise, double a) {
        if (!(distance >= 0) || !Double.isFinite(distance)) {
            throw new IllegalArgumentException("distance must be finite and >= 0, was " + distance);
        }
        if (!(vCruise > 0) || !(a > 0) || !Double.isFinite(vCruise) || !Double.isFinite(a)) {
            throw new IllegalArgumentException("cruise speed and acceleration must be finite and > 0");
        }
        this.distance = distance;
        this.a = a;
        this.vPeak = Math.min(vCruise, Math.sqrt(a * distance));
        this.tAccel = vPeak > 0 ? vPeak / a : 0;
        double accelDistance = vPeak * tAccel; // both ramps together
        this.tCruise = vPeak > 0 ? (distance - accelDistance) / vPeak : 0;
        this.duration = 2 * tAccel + tCruise;
    }

    @Override
    public double duration() {
        return duration;
    }

    @Override
    public double distance() {
        return distance;
    }

    /** @return the profile's top speed, m/s */
    public double peakSpeed() {
        return vPeak;
    }

    @Override
    public void evaluate(double t, double[] out) {
        if (!Double.isFinite(t)) {
            throw new IllegalArgumentException("time must be finite, was " + t);
        }
        if (t <= 0 || duration == 0) {
            out[0] = t <= 0 ? 0 : distance;
            out[1] = 0;
            out[2] = 0;
        } else if (t < tAccel) {
            out[0] = 0.5 * a * t * t;
            out[1] = a * t;
            out[2] = a;
        } else if (t < tAccel + tCruise) {
            out[0] = 0.5 * a * tAccel * tAccel + vPeak * (t - tAccel);
            out[1] = vPeak;
            out[2] = 0;
        } else if (t < duration) {
            double r = duration - t;
            out[0] = distance - 0.5 * a * r * r;
            out[1] = a * r;
            out[2] = -a;
        } else {
            out[0] = distance;
            out[1] = 0;
            out[2] = 0;
        }
    }
}
