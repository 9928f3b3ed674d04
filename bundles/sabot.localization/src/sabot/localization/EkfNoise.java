package sabot.localization;

/**
 * Noise model of {@link PoseEkf}: process noise spectral densities and the default measurement standard deviations.
 * Defaults are sized for a Bosch BMI088-class MEMS IMU and a 1 % wheel-slip floor (see docs/MOTION.md).
 *
 * @param yawAccelerationPsd   white yaw acceleration driving &omega;, (rad/s&sup2;)&sup2;/Hz
 * @param jerkPsd              white jerk driving the longitudinal acceleration, (m/s&sup3;)&sup2;/Hz
 * @param gyroBiasWalkPsd      gyro bias random walk, (rad/s)&sup2;/s
 * @param accelBiasWalkPsd     accelerometer bias random walk, (m/s&sup2;)&sup2;/s
 * @param odometrySpeedFloor   wheel-odometry speed sigma at rest, m/s
 * @param odometrySpeedSlip    wheel-odometry speed sigma per m/s of speed (slip), dimensionless
 * @param odometryYawRateFloor wheel-odometry yaw-rate sigma at rest, rad/s
 * @param odometryYawRateSlip  wheel-odometry yaw-rate sigma per m/s of speed, rad/m: large, because slip and wheel
 *                             asymmetry corrupt the odometric yaw rate while moving and the gyro is far better
 * @param gyroSigma            gyro sample sigma, rad/s
 * @param accelSigma           accelerometer sample sigma, m/s&sup2;
 * @param magnetometerSigma    heading sigma of the magnetometer, rad
 * @param gateProbability      chi-square probability of the Mahalanobis gate (e.g. 0.999)
 */
public record EkfNoise(double yawAccelerationPsd, double jerkPsd, double gyroBiasWalkPsd, double accelBiasWalkPsd,
        double odometrySpeedFloor, double odometrySpeedSlip, double odometryYawRateFloor, double odometryYawRateSlip,
        double gyroSigma, double accelSigma, double magnetometerSigma, double gateProbability) {

    public EkfNoise {
        for (double v : new double[] { yawAccelerationPsd, jerkPsd, gyroBiasWalkPsd, accelBiasWalkPsd,
                odometrySpeedFloor, odometrySpeedSlip, odometryYawRateFloor, odometryYawRateSlip, gyroSigma,
                accelSigma, magnetometerSigma }) {
            if (!(v > 0) || !Double.isFinite(v)) {
                throw new IllegalArgumentException("EKF noise parameters must be finite and > 0, got " + v);
            }
        }
        if (!(gateProbability > 0.5 && gateProbability < 1)) {
            throw new IllegalArgumentException("gate probability must be in (0.5, 1), got " + gateProbability);
        }
    }

    /**
     * Defaults: gyro 1.7 mrad/s per sample (0.014 &deg;/s/&radic;Hz over a 50 Hz band: conservative against
     * the 25 Hz output filter the simulator assumes), bias walk 2e-5 rad/s/&radic;s,
     * accelerometer 175 &micro;g/&radic;Hz over a 25 Hz band (8.6 mm/s&sup2;), magnetometer heading 2&deg;,
     * odometry speed 0.5 mm/s plus 0.7 % of the speed (1 % independent slip on each wheel), odometry yaw rate
     * 1 mrad/s at rest growing 0.2 rad/m with speed, 99.9 % gate.
     */
    public static EkfNoise defaults() {
        return new EkfNoise(1.0, 1.0, 4e-10, 1e-6, 0.0005, 0.007, 0.001, 0.2, 1.7e-3, 8.6e-3, Math.toRadians(2), 0.999);
    }
}
