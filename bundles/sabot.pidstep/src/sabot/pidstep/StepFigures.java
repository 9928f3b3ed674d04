package sabot.pidstep;

import java.util.List;

/**
 * The figures of a step response that a person tunes a loop by: rise time, overshoot and settling time. Pure
 * computation on the samples (no OSGi, no UI), the same on the robot and in the workbench.
 * <p>
 * Definitions (the usual ones, e.g. Ogata, <i>Modern Control Engineering</i>, 5.3): the step is the final set-point
 * {@code s} (the last sample's; a step test holds it constant after t = 0). <b>Rise time</b>: from the first sample at
 * or beyond 10 % of {@code s} to the first at or beyond 90 %. <b>Overshoot</b>: the largest excursion beyond {@code s}
 * in the step's direction, in percent of {@code |s|} (0 when the response never passes it). <b>Settling time</b>: the
 * time of the first sample from which on every sample stays within ±{@code band} of {@code s}. A figure the samples
 * do not show (a response that never reaches 90 %, or is still outside the band at its end) is {@link Double#NaN}.
 *
 * @param riseTime     s, or NaN
 * @param overshoot    % of the step, &ge; 0
 * @param settlingTime s, or NaN
 * @param finalError   the last sample's set-point minus measured value, in the samples' unit
 * @param band         the settling band used, a fraction of the step (e.g. 0.02)
 */
public record StepFigures(double riseTime, double overshoot, double settlingTime, double finalError, double band) {

    /** The settling band of {@link #of(List)}: 2 %. */
    public static final double DEFAULT_BAND = 0.02;

    /** @return the figures with a 2 % settling band */
    public static StepFigures of(List<StepSample> samples) {
        return of(samples, DEFAULT_BAND);
    }

    /**
     * @param samples in time order, at least two; the last one's set-point is the step and must not be 0
     * @param band    settling band as a fraction of the step, in (0, 1)
     * @throws IllegalArgumentException for fewer than two samples, times that decrease, a zero step or a band outside
     *                                  (0, 1)
     */
    public static StepFigures of(List<StepSample> samples, double band) {
        if (samples.size() < 2) {
            throw new IllegalArgumentException("a step response needs at least 2 samples, has " + samples.size());
        }
        if (!(band > 0 && band < 1)) {
            throw new IllegalArgumentException("settling band " + band + " is not in (0, 1)");
        }
        StepSample last = samples.get(samples.size() - 1);
        double step = last.setPoint();
        if (step == 0 || !Double.isFinite(step)) {
            throw new IllegalArgumentException("the step (the last set-point) is " + step);
        }
        // work in the step's direction, so that a negative step has the same figures as its mirror image
        double sign = Math.signum(step);
        double size = Math.abs(step);
        double t10 = Double.NaN;
        double t90 = Double.NaN;
        double peak = Double.NEGATIVE_INFINITY;
        double settled = samples.get(0).t();
        double previous = Double.NEGATIVE_INFINITY;
        for (StepSample s : samples) {
            if (s.t() < previous) {
                throw new IllegalArgumentException("sample times decrease at t = " + s.t() + " s");
            }
            previous = s.t();
            double y = sign * s.measured();
            if (Double.isNaN(t10) && y >= 0.1 * size) {
                t10 = s.t();
            }
            if (Double.isNaN(t90) && y >= 0.9 * size) {
                t90 = s.t();
            }
            peak = Math.max(peak, y);
            if (Math.abs(y - size) > band * size) {
                settled = Double.NaN; // outside: settling starts again at the next sample inside
            } else if (Double.isNaN(settled)) {
                settled = s.t();
            }
        }
        double overshoot = Math.max(0, (peak - size) / size * 100);
        return new StepFigures(t90 - t10, overshoot, settled, step - last.measured(), band);
    }
}
