package sabot.modbus;

import java.time.Duration;

/**
 * A position step response as the SACT board recorded it (map file {@code step_capture}): sample k was measured
 * k × {@link #samplePeriod()} after the step, at the control interrupt.
 *
 * @param motor        the motor stepped
 * @param samplePeriod time between two samples
 * @param counts       measured position minus the position at the step, encoder counts; as many as the board has
 *                     recorded so far (all of them once {@link #complete()})
 * @param capacity     samples a complete recording has
 */
public record StepCapture(Motor motor, Duration samplePeriod, int[] counts, int capacity) {

    /** @return whether the board has recorded every sample */
    public boolean complete() {
        return counts.length == capacity;
    }
}
