package sabot.modbus;

/**
 * One sample of the inertial board, body frame (x forward, y left, z up), read in one sub-request.
 *
 * @param counter     sample counter, 0–65535, wraps: a new value means a new sample
 * @param gyroX       angular rate about x, rad/s
 * @param gyroY       angular rate about y, rad/s
 * @param gyroZ       angular rate about z (yaw rate), rad/s
 * @param accelX      specific force along x, m/s²
 * @param accelY      specific force along y, m/s²
 * @param accelZ      specific force along z, m/s² (+g at rest)
 * @param magX        magnetic field along x, T
 * @param magY        magnetic field along y, T
 * @param magZ        magnetic field along z, T
 * @param temperature die temperature, °C
 */
public record InsSample(int counter, double gyroX, double gyroY, double gyroZ, double accelX, double accelY,
        double accelZ, double magX, double magY, double magZ, double temperature) {
}
