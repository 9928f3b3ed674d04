package sabot.model.robot;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import java.time.Instant;

import org.junit.jupiter.api.Test;

class BatteryStateTest {

    private static final Instant T = Instant.parse("2026-12-01T10:00:00Z");

    private static String refusal(double soc, double volts, double amps, double capacity, boolean docked,
            boolean charging, boolean full) {
        return assertThrows(IllegalArgumentException.class,
                () -> new BatteryState(T, soc, volts, amps, capacity, docked, charging, full)).getMessage();
    }

    @Test
    void aReadingNoBatteryGivesIsRefusedNamingTheValue() {
        assertEquals("battery state of charge 1.2 is outside 0..1", refusal(1.2, 25, 0.6, 10, false, false, false));
        assertEquals("battery state of charge -0.01 is outside 0..1", refusal(-0.01, 25, 0.6, 10, false, false, false));
        assertEquals("battery state of charge NaN is outside 0..1", refusal(Double.NaN, 25, 0.6, 10, false, false,
                false));
        assertEquals("battery voltage 0.0 V is not a positive number", refusal(0.5, 0, 0.6, 10, false, false, false));
        assertEquals("battery voltage Infinity V is not a positive number", refusal(0.5, Double.POSITIVE_INFINITY, 0.6,
                10, false, false, false));
        assertEquals("battery current NaN A is not a number", refusal(0.5, 25, Double.NaN, 10, false, false, false));
        assertEquals("battery design capacity 0.0 Ah is not a positive number", refusal(0.5, 25, 0.6, 0, false, false,
                false));
        assertEquals("battery charging away from a dock", refusal(0.5, 25, -5, 10, false, true, false));
        assertEquals("battery full away from a dock", refusal(1, 25, 0, 10, false, false, true));
        assertEquals("battery both charging and full", refusal(1, 25, 0, 10, true, true, true));
        assertThrows(NullPointerException.class, () -> new BatteryState(null, 0.5, 25, 0.6, 10, false, false, false));
    }

    @Test
    void remainingChargeIsTheFractionOfTheDesignCapacity() {
        BatteryState b = new BatteryState(T, 0.25, 24.9, -5.0, 10.0, true, true, false);
        assertEquals(2.5, b.remainingCharge(), 1e-12);
        assertEquals("battery 25.0 % 24.90 V -5.00 A, docked, charging", b.summary());
        assertEquals("battery 100.0 % 29.40 V 0.00 A, docked, full",
                new BatteryState(T, 1, 29.4, 0, 10, true, false, true).summary());
    }
}
