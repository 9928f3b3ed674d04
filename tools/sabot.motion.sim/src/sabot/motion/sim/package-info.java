/**
 * Deterministic simulation harness for Sabot's motion stack: a ground-truth differential-drive robot with wheel
 * slip (random and biased), quantised encoders and a MEMS IMU with noise, bias and bias random walk; the paper's
 * scenarios (Bernoulli lemniscate, circle, square with stops, start offset, point stabilization) for the study of the
 * control laws and estimators ({@link sabot.motion.sim.Simulation}), and the robot's own control loop closed over the
 * same simulated robot ({@link sabot.motion.sim.OnboardLoop}). The
 * {@code ./sabot simulate} command line with its CSV and PNG output is {@code sabot.tools.simulate.SimulateCommand}
 * (tools/sabot.tools).
 * <p>
 * Every random draw comes from generators seeded from the run's seed ({@link sabot.motion.sim.SimulationConfig#seed()},
 * or {@link sabot.motion.sim.OnboardLoop#toGoal}'s): the same configuration gives bit-identical results.
 */
package sabot.motion.sim;
