package sabot.controlml.payload;

import java.util.Objects;

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
}
