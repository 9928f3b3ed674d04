package sabot.modbus;

/**
 * Both wheels' encoder positions read in one transaction.
 *
 * @param left  left motor's measured position, quadrature counts (wraps modulo 2^32)
 * @param right right motor's measured position, quadrature counts (wraps modulo 2^32)
 */
public record WheelCounts(int left, int right) {
}
