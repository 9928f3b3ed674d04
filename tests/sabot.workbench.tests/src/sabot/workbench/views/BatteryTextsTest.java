package sabot.workbench.views;

import static org.junit.jupiter.api.Assertions.assertEquals;

import java.time.Instant;

import org.junit.jupiter.api.Test;

import sabot.model.robot.BatteryState;
import sabot.workbench.fleet.RobotState;

/** The battery as the Fleet view's column and the map's label say it (docs/WORKBENCH.md). */
class BatteryTextsTest {

    private static final Instant AT = Instant.parse("2026-11-29T12:00:00Z");

    @Test
    void theFleetColumnSaysChargeVoltageAndWhatTheDockDoes() {
        assertEquals("–", FleetView.battery(null));
        assertEquals("87 % · 25.31 V", FleetView.battery(new BatteryState(AT, 0.87, 25.314, 0.6, 10, false, false,
                false)));
        assertEquals("20 % · 24.10 V · charging", FleetView.battery(new BatteryState(AT, 0.204, 24.1, -4, 10, true,
                true, false)));
        assertEquals("100 % · 29.40 V · full", FleetView.battery(new BatteryState(AT, 1, 29.4, 0, 10, true, false,
                true)));
        assertEquals("55 % · 26.00 V · docked", FleetView.battery(new BatteryState(AT, 0.55, 26, 0.5, 10, true, false,
                false)));
    }

    @Test
    void theMapsLabelShowsTheChargeOnlyOnceMeasured() {
        RobotState r = RobotState.unknown("sabot-01@sabot.local", "sabot-01");
        assertEquals("", RobotPainter.battery(r));
        assertEquals(" 42 %", RobotPainter.battery(r.withBattery(new BatteryState(AT, 0.42, 25, 0.6, 10, false, false,
                false), AT)));
        assertEquals(" 42 % charging", RobotPainter.battery(r.withBattery(new BatteryState(AT, 0.42, 25, -3, 10, true,
                true, false), AT)));
        assertEquals(AT, r.withBattery(new BatteryState(AT, 0.42, 25, 0.6, 10, false, false, false), AT)
                .lastTelemetry(), "a reading is telemetry");
    }
}
