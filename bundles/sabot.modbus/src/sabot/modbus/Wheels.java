package sabot.modbus;

/**
 * Both wheels, read in one transaction (so both belong to the same moment, within a control period).
 *
 * @param left  the left wheel
 * @param right the right wheel
 */
public record Wheels(WheelState left, WheelState right) {
}
