package sabot.controlml.payload;

import java.time.Instant;
import java.util.Objects;

import sabot.model.geometry.Pose2D;

/**
 * {@code cm.position}: the localizer's pose estimate in the map frame.
 *
 * @param time       when the estimate was valid; never null
 * @param pose       x, y in metres, theta in radians; never null
 * @param covariance its uncertainty; never null
 */
public record PoseEstimate(Instant time, Pose2D pose, PoseCovariance covariance) {
    public PoseEstimate {
        Objects.requireNonNull(time, "time");
        Objects.requireNonNull(pose, "pose");
        Objects.requireNonNull(covariance, "covariance");
    }
}
