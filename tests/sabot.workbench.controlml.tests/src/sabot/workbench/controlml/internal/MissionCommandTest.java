package sabot.workbench.controlml.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Instant;
import java.util.ArrayList;
import java.util.List;

import org.junit.jupiter.api.Test;

import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.controlml.payload.MissionTarget.Action;
import sabot.model.geometry.Pose2D;
import sabot.workbench.fleet.RobotState;

/**
 * What {@code FleetState.startMission} sends ({@link ControlMlFleet#missionCommand}) and when the plug-in fetches a
 * robot's plan anew ({@link FleetTelemetry#newPlan}): each leg of a mission of several targets has its own.
 */
class MissionCommandTest {

    private static final List<MissionTarget> TARGETS = List.of(
            MissionTarget.pending(goal(1, 2, 0), Action.PASS, 0),
            MissionTarget.pending(goal(3, 2, 1.5), Action.WAIT, 7.5),
            MissionTarget.pending(goal(3, 5, 3.1), Action.DOCK, 0));

    private static Goal goal(double x, double y, double theta) {
        return new Goal(new Pose2D(x, y, theta), 0.1, 0.2);
    }

    @Test
    void aMissionStartsAsRunningOrQueuesAsQueuedWithItsTargetsPendingAndRoundTrips() throws Exception {
        MissionStatus now = ControlMlFleet.missionCommand(null, TARGETS, false);
        assertEquals(new MissionStatus(MissionState.RUNNING, false, 0, "", TARGETS, 0, 0), now);
        MissionStatus queued = ControlMlFleet.missionCommand(null, TARGETS, true);
        assertEquals(MissionState.QUEUED, queued.state());
        // the record the robot decodes is the one sent
        assertEquals(queued, MissionStatus.CODEC.decode(MissionStatus.CODEC.encode(queued)));
    }

    @Test
    void targetsAreSentPendingWhateverStateTheyCarryAndTheRobotsMaintenanceFlagIsKept() {
        List<MissionTarget> reached = TARGETS.stream().map(t -> t.in(MissionTarget.State.REACHED)).toList();
        RobotState inMaintenance = RobotState.unknown("r@x", "r").withMission(new MissionStatus(MissionState.IDLE,
                true, 0, ""), Instant.EPOCH);
        MissionStatus m = ControlMlFleet.missionCommand(inMaintenance, reached, false);
        assertEquals(TARGETS, m.targets());
        // the robot's own flag: the robot reads no maintenance switch (which it refuses with targets) and says why
        // it cannot start a mission in maintenance
        assertTrue(m.maintenance());
    }

    @Test
    void noTargetIsRefusedBeforeItCouldBeReadAsAResume() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> ControlMlFleet.missionCommand(
                null, List.of(), false));
        assertEquals("a mission needs at least one target", e.getMessage());
        List<MissionTarget> many = new ArrayList<>();
        for (int i = 0; i <= MissionStatus.MAX_TARGETS; i++) {
            many.add(MissionTarget.pending(goal(i, 0, 0), Action.STOP, 0));
        }
        assertThrows(IllegalArgumentException.class, () -> ControlMlFleet.missionCommand(null, many, false));
    }

    @Test
    void eachLegOfAMissionOfTargetsHasANewPlan() {
        MissionStatus leg0 = running(0);
        assertTrue(FleetTelemetry.newPlan(null, leg0), "a mission seen for the first time");
        assertTrue(FleetTelemetry.newPlan(new MissionStatus(MissionState.IDLE, false, 0, ""), leg0), "a mission starts");
        assertFalse(FleetTelemetry.newPlan(leg0, running(0).with(MissionState.RUNNING, 20, "")), "progress alone");
        assertTrue(FleetTelemetry.newPlan(leg0, running(1)), "the next target");
        MissionStatus other = new MissionStatus(MissionState.RUNNING, false, 0, "", List.of(MissionTarget.pending(
                goal(6, 6, 0), Action.STOP, 0)), 0, 0);
        assertTrue(FleetTelemetry.newPlan(leg0, other), "a mission that replaced the running one");
        assertFalse(FleetTelemetry.newPlan(running(2), running(3).with(MissionState.DONE, 100, "")), "done: no plan");
    }

    private static MissionStatus running(int current) {
        List<MissionTarget> t = new ArrayList<>();
        for (int i = 0; i < TARGETS.size(); i++) {
            t.add(TARGETS.get(i).in(i < current ? MissionTarget.State.REACHED : i == current
                    ? MissionTarget.State.ACTIVE : MissionTarget.State.PENDING));
        }
        return new MissionStatus(MissionState.RUNNING, false, 10 * current, "", t, current, 0);
    }
}
