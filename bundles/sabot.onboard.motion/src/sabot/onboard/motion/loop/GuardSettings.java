package sabot.onboard.motion.loop;

/**
 * The collision guard's settings (the {@code motion} task's {@code guard*} settings and {@code reverseSpeed}); the
 * footprint is the planner's robot radius and the braking deceleration the motion limits' acceleration.
 *
 * @param margin       m the robot stops short of an obstacle
 * @param reactionTime s from a command to the wheels braking, counted as driving on at the commanded speed
 * @param reverseSpeed m/s, the top speed backwards (no sensor looks behind)
 */
public record GuardSettings(double margin, double reactionTime, double reverseSpeed) {
}
