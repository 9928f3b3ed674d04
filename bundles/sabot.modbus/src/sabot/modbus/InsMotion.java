package sabot.modbus;

/**
 * What a control loop needs of the inertial board, read in a short transaction.
 *
 * @param gyroZ  yaw rate, rad/s
 * @param accelX specific force along x (forward), m/s²
 */
public record InsMotion(double gyroZ, double accelX) {
}
