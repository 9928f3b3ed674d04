package sabot.controlml.payload;

/**
 * One sample of a timed trajectory.
 *
 * @param t      seconds since the trajectory's start
 * @param x      metres
 * @param y      metres
 * @param theta  radians
 * @param v      forward speed, m/s
 * @param omega  yaw rate, rad/s
 */
public record TrajectoryPoint(double t, double x, double y, double theta, double v, double omega) {
}
