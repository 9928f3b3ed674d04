package sabot.controlml.payload;

import java.util.Objects;

import sabot.controlml.swe.SweComponent;
import sabot.model.geometry.Pose2D;

/**
 * {@code cm.goal}: where a mission should take the robot.
 *
 * @param pose              target pose in the map frame (m, m, rad); never null
 * @param positionTolerance how close counts as arrived, metres, &gt; 0
 * @param headingTolerance  heading tolerance in radians, &gt; 0
 */
public record Goal(Pose2D pose, double positionTolerance, double headingTolerance) {
    public Goal {
        Objects.requireNonNull(pose, "pose");
    }

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<Goal> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(Goal g) {
            return new RecordBuilder().quantity("x", "m", g.pose().x()).quantity("y", "m", g.pose().y()).quantity(
                    "theta", "rad", g.pose().theta()).quantity("positionTolerance", "m", g.positionTolerance())
                    .quantity("headingTolerance", "rad", g.headingTolerance()).build();
        }

        @Override
        public Goal decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "x", "y", "theta", "positionTolerance", "headingTolerance");
            Pose2D pose = new Pose2D(r.quantity("x", "m"), r.quantity("y", "m"), r.quantity("theta", "rad"));
            return new Goal(pose, r.quantity("positionTolerance", "m", RecordReader.POSITIVE, RecordReader.UNBOUNDED),
                    r.quantity("headingTolerance", "rad", RecordReader.POSITIVE, 2 * Math.PI));
        }
    };
}
