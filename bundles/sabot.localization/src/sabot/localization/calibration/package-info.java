/**
 * Calibration of the odometry's systematic errors from square runs, in the manner of UMBmark (J. Borenstein,
 * L. Feng, "Measurement and correction of systematic odometry errors in mobile robots", IEEE Trans. Robotics and
 * Automation 12(6):869-880, 1996).
 */
package sabot.localization.calibration;
