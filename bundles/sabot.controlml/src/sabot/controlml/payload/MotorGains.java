package sabot.controlml.payload;

/**
 * PID gains of one motor's speed loop, in the SACT board's dimensionless units.
 *
 * @param motor motor index (0 = left, 1 = right)
 * @param kp    proportional gain, &ge; 0
 * @param ki    integral gain, &ge; 0
 * @param kd    derivative gain, &ge; 0
 */
public record MotorGains(int motor, double kp, double ki, double kd) {
}
