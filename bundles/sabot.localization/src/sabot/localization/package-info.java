/**
 * Where the robot is: {@link sabot.localization.EncoderOdometry} integrates wheel encoder counts with the
 * second-order Runge-Kutta update; {@link sabot.localization.PoseEkf} fuses wheel odometry, gyro, accelerometer,
 * magnetometer heading and absolute fixes from ceiling landmarks, gates outliers by Mahalanobis distance and exposes
 * its covariance. Map frame, SI units and radians; times in seconds on the caller's monotonic clock.
 */
package sabot.localization;
