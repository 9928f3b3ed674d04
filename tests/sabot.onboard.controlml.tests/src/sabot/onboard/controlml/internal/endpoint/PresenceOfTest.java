package sabot.onboard.controlml.internal.endpoint;

import static org.junit.jupiter.api.Assertions.assertEquals;

import org.junit.jupiter.api.Test;

import sabot.controlml.PresenceLevel;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;

/** The presence a mission and the battery give: {@code presenceOf} and {@code reasonOf} are pure functions. */
class PresenceOfTest {

    private static final MissionStatus DOCKED = new MissionStatus(MissionState.DONE, false, 100,
            "all 1 targets reached, docked");

    @Test
    void aRobotChargingOnItsDockAfterALowBatteryIsAwayCharging() {
        assertEquals(PresenceLevel.AWAY, ControlMlEndpoint.presenceOf(DOCKED, true));
        assertEquals("charging", ControlMlEndpoint.reasonOf(DOCKED, true));
        assertEquals(PresenceLevel.FREE, ControlMlEndpoint.presenceOf(DOCKED, false), "charged: free again");
        assertEquals("all 1 targets reached, docked", ControlMlEndpoint.reasonOf(DOCKED, false));
        MissionStatus maintenance = new MissionStatus(MissionState.IDLE, true, 0, "");
        assertEquals("maintenance", ControlMlEndpoint.reasonOf(maintenance, true), "maintenance says more");
    }
}
