package sabot.control;

/** What a {@link TrackingController} did on one update. The {@code STOPPED_*} values always carry a zero twist. */
public enum ControlStatus {
    /** Normal tracking law applied. */
    TRACKING,
    /** The reference is (nearly) at rest, so the controller regulates pose with a static law instead. */
    REGULATING_AT_REST,
    /** Dynamic feedback linearization with |&xi;| below its floor: &omega; computed with the floored &xi;. */
    NEAR_SINGULARITY,
    /** The pose estimate had a NaN or infinite component: stop. */
    STOPPED_INVALID_POSE,
    /** The reference sample had a NaN or infinite component: stop. */
    STOPPED_INVALID_REFERENCE,
    /** Time was NaN/infinite or went backwards: stop, and the controller's internal state is reset. */
    STOPPED_INVALID_TIME,
    /** The control law produced a non-finite value (a bug or a degenerate input): stop. */
    STOPPED_NUMERICAL_FAULT;

    /** @return true for the states in which the controller commands a stop */
    public boolean isStop() {
        return name().startsWith("STOPPED");
    }
}
