package sabot.onboard.motion.loop;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Instant;
import java.util.List;
import java.util.Optional;

import org.junit.jupiter.api.Test;

import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.robot.BatteryState;
import sabot.onboard.motion.loop.BatteryGuard.State;

/** The low-battery rules, reading by reading: go to the nearest dock below low, charge, free again when charged. */
class BatteryGuardTest {

    private static final Instant T = Instant.parse("2026-12-01T10:00:00Z");
    private static final List<Point2D> DOCKS = List.of(new Point2D(1, 1), new Point2D(11, 1));
    private static final Pose2D EAST = new Pose2D(9, 4, 0);
    private static final MissionStatus RUNNING = new MissionStatus(MissionState.RUNNING, false, 40, "to (10, 6)");
    private static final MissionStatus DONE = new MissionStatus(MissionState.DONE, false, 100, "");
    private static final MissionStatus ABORTED = new MissionStatus(MissionState.ABORTED, false, 10, "");

    private final BatteryGuard guard = new BatteryGuard(0.2, 0.9, DOCKS);

    private static BatteryState away(double soc) {
        return new BatteryState(T, soc, 25, 0.6, 10, false, false, false);
    }

    private static BatteryState docked(double soc, boolean full) {
        return new BatteryState(T, soc, 27, full ? 0 : -5, 10, true, !full, full);
    }

    @Test
    void belowLowTheRobotGoesToTheNearestDockChargesAndIsFreeWhenCharged() {
        assertEquals(Optional.empty(), guard.update(away(0.21), EAST, RUNNING).goToDock(), "above low");
        BatteryGuard.Decision d = guard.update(away(0.19), EAST, RUNNING);
        assertEquals(Optional.of(new Point2D(11, 1)), d.goToDock(), "the nearest dock");
        assertEquals("battery low (19 %, below 20 %): to the dock at (11.00, 1.00)", d.note());
        assertEquals(State.TO_DOCK, guard.state());
        assertEquals(Optional.empty(), guard.update(away(0.18), EAST, RUNNING).goToDock(), "on its way");
        assertFalse(guard.charging());
        assertEquals("docked at 18 %: charging", guard.update(docked(0.18, false), EAST, DONE).note());
        assertTrue(guard.charging());
        guard.update(docked(0.89, false), EAST, DONE);
        assertTrue(guard.charging(), "below charged");
        assertEquals("charged to 90 %: free again", guard.update(docked(0.9, false), EAST, DONE).note());
        assertEquals(State.NORMAL, guard.state());
    }

    @Test
    void aDockMissionThatEndsElsewhereIsSentAgainWhileTheChargeIsLow() {
        guard.update(away(0.1), EAST, RUNNING);
        assertEquals(Optional.of(new Point2D(11, 1)), guard.update(away(0.1), EAST, ABORTED).goToDock());
    }

    @Test
    void aFullChargeOrLeavingTheDockEndsCharging() {
        guard.update(away(0.1), EAST, RUNNING);
        guard.update(docked(0.1, false), EAST, DONE);
        guard.update(docked(0.85, true), EAST, DONE);
        assertFalse(guard.charging(), "the charge ended full below 90 %");
        guard.update(away(0.1), EAST, RUNNING);
        guard.update(docked(0.1, false), EAST, DONE);
        assertEquals("taken off the dock while charging at 30 %", guard.update(away(0.3), EAST, DONE).note());
        assertFalse(guard.charging());
    }

    @Test
    void inMaintenanceOrOnADockOrWithoutDocksTheRobotStays() {
        assertEquals(Optional.empty(), guard.update(away(0.1), EAST, new MissionStatus(MissionState.IDLE, true, 0,
                "")).goToDock());
        assertEquals(Optional.empty(), guard.update(docked(0.1, false), EAST, DONE).goToDock());
        BatteryGuard none = new BatteryGuard(0.2, 0.9, List.of());
        assertEquals("battery low (10 %) and the map has no dock", none.update(away(0.1), EAST, RUNNING).note());
        assertEquals("", none.update(away(0.1), EAST, RUNNING).note(), "said once");
        assertThrows(IllegalArgumentException.class, () -> new BatteryGuard(0.5, 0.4, DOCKS));
    }
}
