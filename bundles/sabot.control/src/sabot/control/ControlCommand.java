package sabot.control;

import sabot.model.geometry.Twist2D;

/**
 * One controller output: the twist to apply until the next update and why it was chosen.
 *
 * @param twist  (v in m/s, &omega; in rad/s); always finite, zero when {@code status.isStop()}
 * @param status what the controller did
 */
public record ControlCommand(Twist2D twist, ControlStatus status) {

    public ControlCommand {
        if (twist == null || status == null) {
            throw new IllegalArgumentException("twist and status are required");
        }
        if (!twist.isFinite()) {
            throw new IllegalArgumentException("a control command must be finite: " + twist);
        }
    }

    /** @return a zero-twist command with the given stop status */
    public static ControlCommand stop(ControlStatus status) {
        return new ControlCommand(Twist2D.ZERO, status);
    }
}
