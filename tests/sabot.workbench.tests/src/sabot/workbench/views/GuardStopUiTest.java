package sabot.workbench.views;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static sabot.workbench.views.FleetViewUpdatesUiTest.drain;
import static sabot.workbench.views.FleetViewUpdatesUiTest.waitFor;

import java.time.Instant;

import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.workbench.fleet.RobotState;

/**
 * The status line tells, once per stop, that a robot's collision guard stopped it before an obstacle — the robot's
 * words from its mission's detail, on a joystick alone or after a mission's own detail.
 */
class GuardStopUiTest {

    private DrivenFleet fleet;

    @AfterEach
    void closeFleet() {
        if (fleet != null) {
            fleet.close();
            drain();
        }
    }

    private void detail(MissionState state, String detail) {
        Instant at = Instant.now();
        RobotState r = fleet.get(DrivenFleet.jid(0));
        fleet.put(r.withMission(new MissionStatus(state, false, 40, detail), at));
        drain();
    }

    @Test
    void aGuardStopIsToldInTheStatusLineOncePerStop() {
        WorkspaceView workspace = WorkspacePaintUiTest.workspace();
        fleet = new DrivenFleet();
        fleet.put(DrivenFleet.busy(0, 3, 3, 0, Instant.now()));
        drain();

        detail(MissionState.IDLE, "stopped: obstacle 0.31 m ahead"); // a joystick held towards a wall
        waitFor(() -> "driven-000: stopped: obstacle 0.31 m ahead".equals(workspace.lastMessage()), 5,
                () -> "status line: " + workspace.lastMessage());

        workspace.show("something else", false);
        detail(MissionState.IDLE, "stopped: obstacle 0.30 m ahead"); // the same stop, still pushing
        assertEquals("something else", workspace.lastMessage(), "a stop is told once");

        detail(MissionState.IDLE, ""); // free again
        detail(MissionState.RUNNING, "to (6.500, 3.000); stopped: obstacle 0.12 m ahead"); // during a mission
        waitFor(() -> "driven-000: stopped: obstacle 0.12 m ahead".equals(workspace.lastMessage()), 5,
                () -> "status line: " + workspace.lastMessage());
    }
}
