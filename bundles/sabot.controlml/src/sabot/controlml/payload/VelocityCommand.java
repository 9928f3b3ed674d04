package sabot.controlml.payload;

import java.time.Instant;
import java.util.Objects;

import sabot.model.geometry.Twist2D;

/**
 * {@code cm.velocity}: a joystick twist (set) or the current commanded twist (get).
 *
 * @param time  when the operator issued it; never null
 * @param twist linear m/s, angular rad/s; never null
 */
public record VelocityCommand(Instant time, Twist2D twist) {
    public VelocityCommand {
        Objects.requireNonNull(time, "time");
        Objects.requireNonNull(twist, "twist");
    }
}
