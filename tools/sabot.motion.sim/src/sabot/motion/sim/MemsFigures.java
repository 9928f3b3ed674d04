package sabot.motion.sim;

/**
 * Error figures of the simulated inertial sensors.
 *
 * @param gyroNoiseDensity      rad/s/&radic;Hz
 * @param gyroTurnOnBiasSigma   rad/s, drawn once per run
 * @param gyroBiasWalk          rad/s/&radic;s (rate random walk)
 * @param accelNoiseDensity     m/s&sup2;/&radic;Hz
 * @param accelTurnOnBiasSigma  m/s&sup2;, drawn once per run
 * @param accelBiasWalk         m/s&sup2;/&radic;s
 * @param bandwidth             Hz, the sensors' output filter bandwidth (noise sigma = density &times; &radic;bandwidth)
 * @param magnetometerSigma     heading sigma, rad (after hard/soft-iron compensation)
 * @param magnetometerRate      Hz
 */
public record MemsFigures(double gyroNoiseDensity, double gyroTurnOnBiasSigma, double gyroBiasWalk,
        double accelNoiseDensity, double accelTurnOnBiasSigma, double accelBiasWalk, double bandwidth,
        double magnetometerSigma, double magnetometerRate) {

    /**
     * Bosch BMI088 (data sheet BST-BMI088-DS001): gyro rate noise 0.014 &deg;/s/&radic;Hz, zero-rate offset up to
     * &plusmn;1 &deg;/s (drawn with sigma 0.5 &deg;/s), bias stability about 2 &deg;/h (modelled as a 2e-5
     * rad/s/&radic;s rate walk); accelerometer noise 175 &micro;g/&radic;Hz, zero-g offset up to &plusmn;20 mg (sigma
     * 10 mg); 25 Hz output bandwidth at 50 Hz sampling. Magnetometer heading (Bosch BMM150-class, compensated):
     * 2&deg; sigma at 10 Hz.
     */
    public static MemsFigures bmi088() {
        return new MemsFigures(Math.toRadians(0.014), Math.toRadians(0.5), 2e-5, 175e-6 * 9.80665, 0.010 * 9.80665,
                1e-4, 25, Math.toRadians(2), 10);
    }

    /** @return gyro sigma per sample, rad/s */
    public double gyroSigma() {
        return gyroNoiseDensity * Math.sqrt(bandwidth);
    }

    /** @return accelerometer sigma per sample, m/s&sup2; */
    public double accelSigma() {
        return accelNoiseDensity * Math.sqrt(bandwidth);
    }
}
