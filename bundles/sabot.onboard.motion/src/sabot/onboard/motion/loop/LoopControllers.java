package sabot.onboard.motion.loop;

import sabot.control.MotionLimits;
import sabot.control.TrackingController;

/** The control laws the loop runs, made anew for each set of motion limits (the {@code tracker} task's choice). */
public interface LoopControllers {

    /** @return a trajectory-tracking controller for these limits */
    TrackingController tracker(MotionLimits limits);

    /** @return a point stabilizer (brings the robot onto a goal pose) for these limits */
    TrackingController stabilizer(MotionLimits limits);
}
