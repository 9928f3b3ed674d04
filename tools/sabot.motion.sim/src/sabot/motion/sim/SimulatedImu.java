package sabot.motion.sim;

import java.util.Random;

/**
 * A MEMS gyro (yaw axis), longitudinal accelerometer and magnetometer heading, sampled once per control step:
 * measurement = true mean value over the step + bias + white noise; biases start at a turn-on offset and random-walk.
 */
public final class SimulatedImu {

    private final MemsFigures figures;
    private final Random rng;
    private double gyroBias;
    private double accelBias;

    public SimulatedImu(MemsFigures figures, long seed) {
        this.figures = figures;
        this.rng = new Random(seed);
        this.gyroBias = figures.gyroTurnOnBiasSigma() * rng.nextGaussian();
        this.accelBias = figures.accelTurnOnBiasSigma() * rng.nextGaussian();
    }

    /** Advances the bias random walks by {@code dt} seconds. */
    public void advance(double dt) {
        gyroBias += figures.gyroBiasWalk() * Math.sqrt(dt) * rng.nextGaussian();
        accelBias += figures.accelBiasWalk() * Math.sqrt(dt) * rng.nextGaussian();
    }

    /** @return a gyro sample for the true mean yaw rate {@code trueRate}, rad/s */
    public double gyro(double trueRate) {
        return trueRate + gyroBias + figures.gyroSigma() * rng.nextGaussian();
    }

    /** @return an accelerometer sample for the true mean longitudinal acceleration, m/s&sup2; */
    public double accelerometer(double trueAcceleration) {
        return trueAcceleration + accelBias + figures.accelSigma() * rng.nextGaussian();
    }

    /** @return a magnetometer heading sample for the true heading, rad */
    public double heading(double trueHeading) {
        return trueHeading + figures.magnetometerSigma() * rng.nextGaussian();
    }

    /** @return the current true gyro bias, rad/s (for reports) */
    public double gyroBias() {
        return gyroBias;
    }
}
