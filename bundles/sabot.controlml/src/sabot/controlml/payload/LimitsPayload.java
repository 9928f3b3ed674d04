package sabot.controlml.payload;

import sabot.controlml.swe.SweComponent;

/**
 * {@code cm.limits}: speed and acceleration limits the controller obeys (all &gt; 0), in the order of the payload's
 * fields. The operator-settable part of the robot's envelope as it travels; the controller's own, complete envelope
 * is {@code sabot.control.MotionLimits}.
 *
 * @param maxLinearSpeed         m/s
 * @param maxAngularSpeed        rad/s
 * @param maxLinearAcceleration  m/s&sup2;
 * @param maxAngularAcceleration rad/s&sup2;
 */
public record LimitsPayload(double maxLinearSpeed, double maxAngularSpeed, double maxLinearAcceleration,
        double maxAngularAcceleration) {

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<LimitsPayload> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(LimitsPayload l) {
            return new RecordBuilder().quantity("maxLinearSpeed", "m/s", l.maxLinearSpeed()).quantity(
                    "maxAngularSpeed", "rad/s", l.maxAngularSpeed()).quantity("maxLinearAcceleration", "m/s2", l
                            .maxLinearAcceleration()).quantity("maxAngularAcceleration", "rad/s2", l
                                    .maxAngularAcceleration()).build();
        }

        @Override
        public LimitsPayload decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "maxLinearSpeed", "maxAngularSpeed", "maxLinearAcceleration",
                    "maxAngularAcceleration");
            return new LimitsPayload(r.quantity("maxLinearSpeed", "m/s", RecordReader.POSITIVE, 10),
                    r.quantity("maxAngularSpeed", "rad/s", RecordReader.POSITIVE, 20),
                    r.quantity("maxLinearAcceleration", "m/s2", RecordReader.POSITIVE, 50),
                    r.quantity("maxAngularAcceleration", "rad/s2", RecordReader.POSITIVE, 100));
        }
    };
}
