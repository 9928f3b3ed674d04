package sabot.pidstep;

/**
 * One sample of a step response.
 *
 * @param t        seconds since the step
 * @param setPoint the commanded displacement, in the unit of the test (metres of wheel travel for {@code cm.pid.step})
 * @param measured the measured displacement from the position at the step, same unit
 */
public record StepSample(double t, double setPoint, double measured) {
}
