package sabot.model.robot;

import java.time.Instant;
import java.util.Locale;
import java.util.Objects;

/**
 * The robot's battery as its power board measured it (docs/SACT-MODBUS.md, "Power board"). Immutable; the constructor
 * refuses a reading no battery can give, naming the value, so a broken gauge is a fault a caller reports rather than
 * a charge it believes.
 *
 * @param measured       when the reading was taken (the master's clock when the answer arrived); never null
 * @param stateOfCharge  charge left as a fraction of the design capacity, 0–1
 * @param voltage        terminal voltage, V, finite and positive
 * @param current        battery current, A, finite: positive discharging, negative charging
 * @param designCapacity capacity of the full battery, Ah, finite and positive
 * @param docked         whether the robot's charger contacts touch a dock's
 * @param charging       whether current flows into the battery
 * @param full           whether the charge has ended on a dock (the dock then carries the load)
 */
public record BatteryState(Instant measured, double stateOfCharge, double voltage, double current,
        double designCapacity, boolean docked, boolean charging, boolean full) {

    /** @throws IllegalArgumentException a value outside what a battery can report, named with its value */
    public BatteryState {
        Objects.requireNonNull(measured, "measured");
        if (!(stateOfCharge >= 0 && stateOfCharge <= 1)) {
            throw new IllegalArgumentException("battery state of charge " + stateOfCharge + " is outside 0..1");
        }
        if (!(voltage > 0) || !Double.isFinite(voltage)) {
            throw new IllegalArgumentException("battery voltage " + voltage + " V is not a positive number");
        }
        if (!Double.isFinite(current)) {
            throw new IllegalArgumentException("battery current " + current + " A is not a number");
        }
        if (!(designCapacity > 0) || !Double.isFinite(designCapacity)) {
            throw new IllegalArgumentException("battery design capacity " + designCapacity
                    + " Ah is not a positive number");
        }
        if ((charging || full) && !docked) {
            throw new IllegalArgumentException("battery " + (charging ? "charging" : "full")
                    + " away from a dock");
        }
        if (charging && full) {
            throw new IllegalArgumentException("battery both charging and full");
        }
    }

    /** @return the charge left, Ah */
    public double remainingCharge() {
        return stateOfCharge * designCapacity;
    }

    /** @return e.g. "battery 42.0 % 25.31 V 0.61 A" with ", docked", ", charging", ", full" as they hold, for logs */
    public String summary() {
        return String.format(Locale.ROOT, "battery %.1f %% %.2f V %.2f A%s%s%s", stateOfCharge * 100, voltage, current,
                docked ? ", docked" : "", charging ? ", charging" : "", full ? ", full" : "");
    }
}
