package sabot.controlml.payload;

import java.time.Instant;
import java.util.Objects;

import sabot.controlml.swe.SweComponent;
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

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<VelocityCommand> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(VelocityCommand v) {
            return new RecordBuilder().time("time", v.time()).quantity("linear", "m/s", v.twist().linear()).quantity(
                    "angular", "rad/s", v.twist().angular()).build();
        }

        @Override
        public VelocityCommand decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "time", "linear", "angular");
            // sanity bounds of the protocol; the robot's own limits (cm.limits) clamp further
            return new VelocityCommand(r.time("time"), new Twist2D(r.quantity("linear", "m/s", -10, 10), r.quantity(
                    "angular", "rad/s", -20, 20)));
        }
    };
}
