package sabot.onboard.robot;

import org.osgi.annotation.versioning.ConsumerType;

import sabot.controlml.payload.MissionStatus;

/** Observer of the robot's mission (presence levels follow it: Free idle, Busy running, Away in maintenance/fault). */
@FunctionalInterface
@ConsumerType
public interface MotionListener {

    /** The mission's state, progress band or detail changed. Called on a notifier thread, never the control loop's. */
    void missionChanged(MissionStatus status);
}
