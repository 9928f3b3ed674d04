package sabot.onboard.motion.loop;

import java.util.List;

import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionStatus;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;

/**
 * What the control loop needs of whoever runs it (the {@code motion} task on the robot; a test or the motion
 * simulation elsewhere). Every call comes from the loop's thread and must not block it.
 */
public interface LoopHost {

    /**
     * A plan the loop asks for: from where the robot stands through the mission's pass targets ({@code via}, in order)
     * to its goal, around the echoes it remembers.
     */
    record PlanRequest(Pose2D from, List<Goal> via, Goal goal, List<Point2D> obstacles) {
        public PlanRequest {
            via = List.copyOf(via);
        }

        /** A plan straight to the goal. */
        public PlanRequest(Pose2D from, Goal goal, List<Point2D> obstacles) {
            this(from, List.of(), goal, obstacles);
        }
    }

    /**
     * The mission's status changed: publish it at once (before the loop logs it), so whoever reacts reads the new
     * state.
     */
    void missionChanged(MissionStatus status);

    /**
     * Plan off the loop's thread ({@link ControlLoop#planPath}) and hand the result back on the loop's thread with
     * {@link ControlLoop#replanned}.
     */
    void planRequested(PlanRequest request);

    /**
     * Apply the commands other threads have queued for the loop, now (the loop calls this mid-period while a joystick
     * drives, so that a twist that arrived during the encoder read goes out with this period's wheel write).
     */
    void applyPendingCommands();
}
