package sabot.onboard.motion.loop;

import sabot.model.geometry.Point2D;

/**
 * One ping of one sonar sensor, in the robot frame: where the sensor sat, where its beam pointed, and what came back.
 * The beam is a cone of ±{@link EchoMemory#SONAR_HALF_BEAM} around the axis; the nearest reflector in it answers.
 *
 * @param origin the sensor's position, m (forward x, left y)
 * @param axis   the beam's axis at the ping, rad (0: straight ahead)
 * @param range  the echo's range from the sensor, m; {@link EchoMemory#SONAR_MAX_RANGE} when nothing answered
 * @param echo   true when something answered within the maximum range
 */
public record SonarPing(Point2D origin, double axis, double range, boolean echo) {

    /** @return a ping that heard nothing within the maximum range */
    public static SonarPing silence(Point2D origin, double axis) {
        return new SonarPing(origin, axis, EchoMemory.SONAR_MAX_RANGE, false);
    }
}
