package sabot.control.internal;

import sabot.control.ControlStatus;
import sabot.model.geometry.Pose2D;
import sabot.model.path.TrajectorySample;

/** The checks every tracking controller makes before its law: a usable time step, pose estimate and reference. */
final class ControllerInputs {

    private ControllerInputs() {
    }

    /**
     * @param dt the step from {@link ControllerClock#advance} (negative when the time was refused)
     * @return the stop status for the first input that cannot be used, or null when all can
     */
    static ControlStatus refusal(double dt, Pose2D estimate, TrajectorySample reference) {
        if (dt < 0) {
            return ControlStatus.STOPPED_INVALID_TIME;
        }
        if (estimate == null || !estimate.isFinite()) {
            return ControlStatus.STOPPED_INVALID_POSE;
        }
        if (reference == null || !reference.isFinite()) {
            return ControlStatus.STOPPED_INVALID_REFERENCE;
        }
        return null;
    }
}
