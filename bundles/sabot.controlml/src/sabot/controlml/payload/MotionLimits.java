package sabot.controlml.payload;

import sabot.controlml.swe.SweComponent;

/**
 * {@code cm.limits}: speed and acceleration limits the controller obeys (all &gt; 0).
 *
 * @param maxLinearSpeed         m/s
 * @param maxAngularSpeed        rad/s
 * @param maxLinearAcceleration  m/s&sup2;
 * @param maxAngularAcceleration rad/s&sup2;
 */
public record MotionLimits(double maxLinearSpeed, double maxAngularSpeed, double maxLinearAcceleration,
        double maxAngularAcceleration) {

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<MotionLimits> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(MotionLimits l) {
            return new RecordBuilder().quantity("maxLinearSpeed", "m/s", l.maxLinearSpeed()).quantity(
                    "maxAngularSpeed", "rad/s", l.maxAngularSpeed()).quantity("maxLinearAcceleration", "m/s2", l
                            .maxLinearAcceleration()).quantity("maxAngularAcceleration", "rad/s2", l
                                    .maxAngularAcceleration()).build();
        }

        @Override
        public MotionLimits decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "maxLinearSpeed", "maxAngularSpeed", "maxLinearAcceleration",
                    "maxAngularAcceleration");
            return new MotionLimits(r.quantity("maxLinearSpeed", "m/s", RecordReader.POSITIVE, 10),
                    r.quantity("maxAngularSpeed", "rad/s", RecordReader.POSITIVE, 20),
                    r.quantity("maxLinearAcceleration", "m/s2", RecordReader.POSITIVE, 50),
                    r.quantity("maxAngularAcceleration", "rad/s2", RecordReader.POSITIVE, 100));
        }
    };
}
