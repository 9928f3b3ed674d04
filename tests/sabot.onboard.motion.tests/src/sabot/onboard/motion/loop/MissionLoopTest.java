package sabot.onboard.motion.loop;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.ArrayList;
import java.util.List;

import org.junit.jupiter.api.Test;

import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.controlml.payload.MissionTarget.Action;
import sabot.controlml.payload.MissionTarget.State;
import sabot.model.geometry.Pose2D;
import sabot.onboard.motion.loop.LoopHost.PlanRequest;

/**
 * Missions of several targets in the control loop, ticked period by period on fake boards and a fake clock (the plans
 * the loop asks for are answered at once, as the planner's thread does within a period): the order, what each action
 * does to the wheels, the progress, the queue, and how a mission ends short of its targets.
 */
class MissionLoopTest {

    private static final double PERIOD = 0.02;

    private final LoopRig rig = new LoopRig();

    private static MissionTarget target(double x, double y, double theta, Action action, double wait) {
        return MissionTarget.pending(new Goal(new Pose2D(x, y, theta), 0.1, 0.2), action, wait);
    }

    private static final List<MissionTarget> FOUR = List.of(target(4, 5, 0, Action.PASS, 0), target(6, 5, 0,
            Action.WAIT, 2), target(6, 7, Math.PI / 2, Action.STOP, 0), target(3.5, 7, Math.PI, Action.STOP, 0));

    private void start(List<MissionTarget> targets) {
        loop().startMission(targets);
    }

    private ControlLoop loop() {
        return rig.loop;
    }

    /** One period, then the plans asked for in it answered. */
    private ControlLoop.Snapshot tick() {
        ControlLoop.Snapshot s = rig.tick();
        rig.answerPlanRequests();
        return s;
    }

    @Test
    void targetsAreReachedInOrderPassingWithoutStoppingAndWaitingTheirTime() {
        rig.run(0.1);
        start(FOUR);
        ControlLoop.Snapshot s = tick();
        assertEquals(MissionState.RUNNING, s.mission().state());
        assertEquals(4, s.mission().targets().size());
        List<Integer> reachedOrder = new ArrayList<>();
        double passSpeed = Double.NaN;
        double waitStart = Double.NaN;
        double waitEnd = Double.NaN;
        double fastestWhileWaiting = 0;
        double progress = 0;
        double t = 0;
        for (int i = 0; i < 120 * 50 && s.mission().state() == MissionState.RUNNING; i++) {
            MissionStatus before = s.mission();
            s = tick();
            t += PERIOD;
            MissionStatus m = s.mission();
            assertTrue(m.progress() >= progress - 1e-9, "progress never goes back: " + progress + " → " + m
                    .progress());
            progress = m.progress();
            for (int k = 0; k < 4; k++) {
                if (m.targets().get(k).state() == State.REACHED && before.targets().get(k).state() != State.REACHED) {
                    reachedOrder.add(k);
                    if (k == 1) {
                        waitEnd = t;
                    }
                }
            }
            Pose2D at = s.pose().pose();
            if (Math.hypot(at.x() - 4, at.y() - 5) <= 0.1) {
                passSpeed = Math.min(Double.isNaN(passSpeed) ? Double.MAX_VALUE : passSpeed, Math.abs(s.velocity()
                        .twist().linear()));
            }
            if (m.detail().startsWith("waiting") && Double.isNaN(waitStart)) {
                waitStart = t;
            }
            if (!Double.isNaN(waitStart) && Double.isNaN(waitEnd)) {
                fastestWhileWaiting = Math.max(fastestWhileWaiting, Math.abs(s.velocity().twist().linear()));
            }
        }
        assertEquals(MissionState.DONE, s.mission().state(), s.mission().detail());
        assertEquals(List.of(0, 1, 2, 3), reachedOrder, "each target once, in order");
        assertTrue(passSpeed > 0.2, "drove through the pass target, slowest " + passSpeed + " m/s within its tolerance");
        assertEquals(2.0, waitEnd - waitStart, 2 * PERIOD, "stood the wait target's 2 s");
        assertTrue(fastestWhileWaiting < 0.02, "still while waiting: " + fastestWhileWaiting + " m/s");
        Pose2D at = s.pose().pose();
        assertTrue(Math.hypot(at.x() - 3.5, at.y() - 7) <= 0.1, "at the last target: " + at);
        assertEquals(100, s.mission().progress());
        assertEquals(4, s.mission().current(), "all reached");
        assertTrue(s.mission().targets().stream().allMatch(x -> x.state() == State.REACHED));
        assertTrue(rig.boards.braked(), "braked on the last target");
    }

    @Test
    void anAbortStopsTheRobotMarksItsTargetFailedAndDropsTheQueue() {
        rig.run(0.1);
        start(FOUR);
        assertTrue(loop().enqueue(List.of(target(2, 5, 0, Action.STOP, 0))));
        ControlLoop.Snapshot s = tick();
        assertEquals(1, s.mission().queued());
        while (s.mission().current() < 1) {
            s = tick();
        }
        s = rig.run(0.5);
        assertTrue(Math.abs(s.velocity().twist().linear()) > 0.05, "driving to the second target");
        loop().abort("aborted by the operator");
        s = tick();
        assertEquals(MissionState.ABORTED, s.mission().state());
        assertTrue(s.mission().detail().endsWith("1 queued mission dropped"), s.mission().detail());
        assertEquals(0, s.mission().queued());
        assertEquals(List.of(State.REACHED, State.FAILED, State.PENDING, State.PENDING), s.mission().targets()
                .stream().map(MissionTarget::state).toList());
        assertTrue(rig.boards.braked(), "braked");
        s = rig.run(3);
        assertTrue(Math.abs(s.velocity().twist().linear()) < 0.01, "stays stopped: " + s.velocity());
        assertEquals(MissionState.ABORTED, s.mission().state(), "the dropped mission does not start");
    }

    @Test
    void aQueuedMissionStartsWhenTheRunningOneIsDone() {
        rig.run(0.1);
        assertTrue(loop().enqueue(List.of(target(3, 5, 0, Action.STOP, 0))), "idle: starts at once");
        ControlLoop.Snapshot s = tick();
        assertEquals(MissionState.RUNNING, s.mission().state());
        assertEquals(0, s.mission().queued());
        assertTrue(loop().enqueue(List.of(target(3, 6, Math.PI / 2, Action.PASS, 0), target(2, 6, Math.PI,
                Action.DOCK, 0))));
        s = tick();
        assertEquals(1, s.mission().queued());
        List<MissionState> states = new ArrayList<>();
        for (int i = 0; i < 90 * 50 && !(s.mission().state() == MissionState.DONE && s.mission().queued() == 0 && s
                .mission().targets().size() == 2); i++) {
            s = tick();
            if (states.isEmpty() || states.get(states.size() - 1) != s.mission().state()) {
                states.add(s.mission().state());
            }
        }
        assertEquals(MissionState.DONE, s.mission().state(), s.mission().detail());
        assertEquals("all 2 targets reached, docked", s.mission().detail());
        assertTrue(rig.missions.stream().anyMatch(m -> m.state() == MissionState.DONE && m.targets().size() == 1),
                "the first mission was done before the second began");
        Pose2D at = s.pose().pose();
        assertTrue(Math.hypot(at.x() - 2, at.y() - 6) <= 0.1, "at the dock: " + at);
    }

    @Test
    void aQueueHoldsAtMostItsLimit() {
        rig.run(0.1);
        start(FOUR);
        for (int i = 0; i < MissionStatus.MAX_QUEUED; i++) {
            assertTrue(loop().enqueue(List.of(target(2, 5, 0, Action.STOP, 0))));
        }
        assertFalse(loop().enqueue(List.of(target(2, 5, 0, Action.STOP, 0))), "full");
        assertEquals(MissionStatus.MAX_QUEUED, tick().mission().queued());
    }

    @Test
    void aNextLegThatCannotBePlannedFailsTheMissionWithItsTarget() {
        rig.run(0.1);
        start(List.of(target(3, 5, 0, Action.STOP, 0), target(8, 8, 0, Action.STOP, 0)));
        assertEquals(3, rig.planRequests.get(0).goal().pose().x(), "the first leg is asked for");
        rig.answerPlanRequests();
        ControlLoop.Snapshot s = rig.tick();
        for (int i = 0; i < 60 * 50 && rig.planRequests.isEmpty(); i++) {
            s = rig.tick();
        }
        PlanRequest next = rig.planRequests.remove(0);
        assertEquals(8, next.goal().pose().x(), "the second leg is asked for");
        loop().replanned(next, new ControlLoop.Plan(null, 0, "unreachable goal: walled in"));
        s = rig.tick();
        assertEquals(MissionState.FAILED, s.mission().state());
        assertEquals("target 2 of 2: unreachable goal: walled in", s.mission().detail());
        assertEquals(List.of(State.REACHED, State.FAILED), s.mission().targets().stream().map(MissionTarget::state)
                .toList());
        assertTrue(rig.boards.braked());
    }

    @Test
    void aTargetWhereTheRobotAlreadyStandsIsReachedInPlace() {
        rig.run(0.1);
        // the rig's robot starts at (2, 5) facing east: the first target is its own position, turned north
        start(List.of(target(2, 5, Math.PI / 2, Action.STOP, 0), target(3, 5, 0, Action.STOP, 0), target(3, 5,
                Math.PI, Action.STOP, 0)));
        ControlLoop.Snapshot s = tick();
        for (int i = 0; i < 60 * 50 && s.mission().state() == MissionState.RUNNING; i++) {
            s = tick();
        }
        assertEquals(MissionState.DONE, s.mission().state(), s.mission().detail());
        Pose2D at = s.pose().pose();
        assertTrue(Math.hypot(at.x() - 3, at.y() - 5) <= 0.1, "at the last target: " + at);
        assertEquals(Math.PI, Math.abs(at.theta()), 0.2, "turned on the spot for the third target: " + at);
    }

    @Test
    void aMissionPausedBeforeItsFirstPlanResumesOnATargetWhereTheRobotStands() {
        rig.run(0.1);
        start(List.of(target(2, 5, Math.PI / 2, Action.STOP, 0)));
        loop().pause(); // before the first leg's plan comes: it is dropped, the resume plans again
        rig.answerPlanRequests();
        loop().resume();
        rig.answerPlanRequests(); // a plan with no distance to go: the robot settles on the target
        ControlLoop.Snapshot s = tick();
        for (int i = 0; i < 30 * 50 && s.mission().state() == MissionState.RUNNING; i++) {
            s = tick();
        }
        assertEquals(MissionState.DONE, s.mission().state(), s.mission().detail());
        assertEquals(Math.PI / 2, s.pose().pose().theta(), 0.2, "turned on the spot: " + s.pose().pose());
    }

    @Test
    void aPausedWaitResumesWithTheRestOfItsTime() {
        rig.run(0.1);
        start(List.of(target(3, 5, 0, Action.WAIT, 4), target(4, 5, 0, Action.STOP, 0)));
        ControlLoop.Snapshot s = tick();
        while (!s.mission().detail().startsWith("waiting")) {
            s = tick();
        }
        s = rig.run(1);
        loop().pause();
        s = rig.run(10);
        assertEquals(MissionState.PAUSED, s.mission().state());
        assertEquals(State.ACTIVE, s.mission().targets().get(0).state(), "still waiting on it");
        loop().resume();
        s = rig.run(2.9);
        assertEquals(State.ACTIVE, s.mission().targets().get(0).state(), "3 s of the wait were left");
        s = rig.run(0.2);
        rig.answerPlanRequests();
        s = tick();
        assertEquals(State.REACHED, s.mission().targets().get(0).state());
        assertEquals(1, s.mission().current());
    }
}
