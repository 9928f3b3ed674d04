package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import java.time.Instant;

import org.junit.jupiter.api.Test;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.payload.BatteryPayload;
import sabot.controlml.payload.PayloadException;
import sabot.controlml.payload.RecordBuilder;
import sabot.controlml.swe.SweComponent;
import sabot.model.robot.BatteryState;

/** {@code cm.battery}'s payload (docs/CONTROLML.md section 4): its fields, units and the readings it refuses. */
class BatteryPayloadTest {

    private static final Instant T = Instant.parse("2026-12-01T10:00:00Z");

    private static SweComponent record(String socUnit, double soc, String voltUnit, double volts, double amps,
            boolean docked, boolean charging, boolean full) {
        return new RecordBuilder().time("time", T).quantity("stateOfCharge", socUnit, soc).quantity("voltage",
                voltUnit, volts).quantity("current", "A", amps).quantity("capacity", "A.h", 10).bool("docked", docked)
                .bool("charging", charging).bool("full", full).build();
    }

    @Test
    void aBatteryTravelsInPerCentVoltsAndAmpHours() throws PayloadException {
        BatteryState b = new BatteryState(T, 0.5, 25.25, -4.5, 10, true, true, false);
        assertEquals(b, BatteryPayload.CODEC.decode(BatteryPayload.CODEC.encode(b)));
        assertEquals(new BatteryState(T, 0.5, 25.25, 0.61, 10, false, false, false), BatteryPayload.CODEC.decode(record(
                "1", 0.5, "mV", 25250, 0.61, false, false, false)), "a fraction and millivolts are converted");
    }

    @Test
    void aReadingNoBatteryGivesIsAnInvalidValueNamingIt() {
        PayloadException over = assertThrows(PayloadException.class, () -> BatteryPayload.CODEC.decode(record("%", 120,
                "V", 25, 0.6, false, false, false)));
        assertEquals(ControlMlCondition.INVALID_VALUE, over.error().cmCondition());
        assertEquals("stateOfCharge = 120.0 % is outside [0.0, 100.0]", over.getMessage());
        PayloadException away = assertThrows(PayloadException.class, () -> BatteryPayload.CODEC.decode(record("%", 50,
                "V", 25, -5, false, true, false)));
        assertEquals(ControlMlCondition.INVALID_VALUE, away.error().cmCondition());
        assertEquals("battery charging away from a dock", away.getMessage());
        PayloadException unit = assertThrows(PayloadException.class, () -> BatteryPayload.CODEC.decode(record("%", 50,
                "m", 25, 0.6, false, false, false)));
        assertEquals(ControlMlCondition.WRONG_UNIT, unit.error().cmCondition());
    }
}
