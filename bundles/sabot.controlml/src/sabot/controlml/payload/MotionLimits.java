package sabot.controlml.payload;

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
}
