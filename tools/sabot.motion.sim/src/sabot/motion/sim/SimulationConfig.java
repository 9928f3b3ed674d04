package sabot.motion.sim;

import sabot.model.robot.RobotDescription;
import sabot.model.robot.RobotDescriptions;

/**
 * One simulation's settings.
 *
 * @param scenario         what to drive
 * @param controller       which law
 * @param feedback         which pose the controller sees
 * @param seed             seed of every random generator of the run
 * @param slipNoise        per-step, per-wheel travel multiplier sigma (0.01 = 1 %)
 * @param slipBias         left/right travel asymmetry (0.002 = 0.2 %)
 * @param calibrated       run the UMBmark squares first and give the odometry the corrected geometry
 * @param robot            the robot description (constants and limits)
 * @param mems             inertial sensor figures
 * @param settleTime       seconds at rest before the reference starts (IMU bias estimation at start-up)
 * @param holdTime         seconds the reference holds its end pose before the run stops
 * @param odometryDropout  time (s, reference clock) after which the encoders stop reporting; NaN for never
 * @param fromVertex       start the lemniscate at its vertex instead of its crossing point
 */
public record SimulationConfig(Scenario scenario, ControllerKind controller, Feedback feedback, long seed,
        double slipNoise, double slipBias, boolean calibrated, RobotDescription robot, MemsFigures mems,
        double settleTime, double holdTime, double odometryDropout, boolean fromVertex) {

    public SimulationConfig {
        if (scenario == null || controller == null || feedback == null || robot == null || mems == null) {
            throw new IllegalArgumentException("scenario, controller, feedback, robot and sensor figures are required");
        }
        if (!(slipNoise >= 0) || slipNoise > 0.5) {
            throw new IllegalArgumentException("slip noise must be in [0, 0.5], was " + slipNoise);
        }
        if (!(Math.abs(slipBias) <= 0.5)) {
            throw new IllegalArgumentException("slip bias must be in [-0.5, 0.5], was " + slipBias);
        }
        if (!(settleTime >= 0) || !(holdTime >= 0)) {
            throw new IllegalArgumentException("settle and hold times must be >= 0");
        }
    }

    /** @return the defaults: seed 1, no slip, the reference robot, BMI088 figures, 2 s settle, 2 s hold */
    public static SimulationConfig of(Scenario scenario, ControllerKind controller, Feedback feedback) {
        return new SimulationConfig(scenario, controller, feedback, 1, 0, 0, false, RobotDescriptions.defaults(),
                MemsFigures.bmi088(), 2.0, 2.0, Double.NaN, false);
    }

    public SimulationConfig withSeed(long s) {
        return new SimulationConfig(scenario, controller, feedback, s, slipNoise, slipBias, calibrated, robot, mems,
                settleTime, holdTime, odometryDropout, fromVertex);
    }

    public SimulationConfig withSlip(double noise, double bias) {
        return new SimulationConfig(scenario, controller, feedback, seed, noise, bias, calibrated, robot, mems,
                settleTime, holdTime, odometryDropout, fromVertex);
    }

    public SimulationConfig withCalibrated(boolean c) {
        return new SimulationConfig(scenario, controller, feedback, seed, slipNoise, slipBias, c, robot, mems,
                settleTime, holdTime, odometryDropout, fromVertex);
    }

    public SimulationConfig withOdometryDropout(double t) {
        return new SimulationConfig(scenario, controller, feedback, seed, slipNoise, slipBias, calibrated, robot, mems,
                settleTime, holdTime, t, fromVertex);
    }

    public SimulationConfig with(Scenario s, ControllerKind c, Feedback f) {
        return new SimulationConfig(s, c, f, seed, slipNoise, slipBias, calibrated, robot, mems, settleTime, holdTime,
                odometryDropout, fromVertex);
    }

    public SimulationConfig withFromVertex(boolean v) {
        return new SimulationConfig(scenario, controller, feedback, seed, slipNoise, slipBias, calibrated, robot, mems,
                settleTime, holdTime, odometryDropout, v);
    }

    public SimulationConfig withRobot(RobotDescription r) {
        return new SimulationConfig(scenario, controller, feedback, seed, slipNoise, slipBias, calibrated, r, mems,
                settleTime, holdTime, odometryDropout, fromVertex);
    }
}
