package sabot.control.figures;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

import sabot.controlml.payload.MissionState;
import sabot.model.robot.RobotDescriptions;
import sabot.motion.sim.OnboardLoop;

/**
 * The robot's own control loop driven to a goal on the simulated robot (seed 1; docs/MOTION.md gives the figures): the
 * mission ends done, and the simulated truth, not only the loop's estimate, stands at the goal.
 */
class OnboardLoopFiguresTest {

    @Test
    void robotsLoopBringsTheSimulatedRobotToItsGoal() {
        OnboardLoop.Run run = OnboardLoop.referenceMission(RobotDescriptions.defaults(), 1);
        // the figures' line, as ./sabot simulate prints its own
        System.out.println(run.toJson(1, OnboardLoop.REFERENCE_SLIP_NOISE, OnboardLoop.REFERENCE_SLIP_BIAS));
        assertEquals(MissionState.DONE, run.mission().state(), run.mission().detail());
        double tolerance = OnboardLoop.REFERENCE_GOAL.positionTolerance();
        assertTrue(run.finalError() <= tolerance, "true distance to the goal " + run.finalError());
        assertTrue(run.finalHeadingError() <= OnboardLoop.REFERENCE_GOAL.headingTolerance(),
                "true heading error " + run.finalHeadingError());
        assertEquals(0, run.limitViolations());
        assertEquals(0, run.nanCommands());
    }
}
