package sabot.onboard.robot;

import sabot.controlml.ControlMlCondition;

/**
 * A command the robot did not take; nothing changed. Carries the ControlML condition the endpoint answers with, and a
 * text for the operator (e.g. "goal (12.40, 3.00) is inside an obstacle").
 */
public final class CommandRefused extends Exception {

    private static final long serialVersionUID = 1L;

    private final transient ControlMlCondition condition;

    /**
     * @param condition why, as a ControlML condition (INVALID_VALUE, INVALID_STATE, BUSY, DEVICE_FAULT, ...)
     * @param message   what the operator reads
     */
    public CommandRefused(ControlMlCondition condition, String message) {
        super(message);
        this.condition = condition;
    }

    /** @return the ControlML condition of the refusal; never null */
    public ControlMlCondition condition() {
        return condition;
    }
}
