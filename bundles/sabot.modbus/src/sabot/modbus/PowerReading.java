package sabot.modbus;

/**
 * The latest measurement of the power board (slave 5): the battery's fuel gauge and the charger contacts. Values
 * within the register map's bounds (the driver refuses others as {@link BoardException.Kind#IMPLAUSIBLE}).
 *
 * @param sequence      measurement counter, 0–65535, wraps: a new value means a new measurement
 * @param voltage       terminal voltage, V (1 mV resolution), the mean over the board's period
 * @param current       battery current, A (1 mA resolution), the mean over the period: positive discharging,
 *                      negative charging
 * @param stateOfCharge charge left as a fraction of the design capacity, 0–1 (10⁻⁴ resolution)
 * @param docked        the charger contacts touch a dock's
 * @param charging      current flows into the battery
 * @param full          the charge has ended on the dock
 */
public record PowerReading(int sequence, double voltage, double current, double stateOfCharge, boolean docked,
        boolean charging, boolean full) {
}
