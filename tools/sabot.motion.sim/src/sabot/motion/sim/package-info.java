/**
 * Deterministic simulation harness for Sabot's motion stack: a ground-truth differential-drive robot with wheel
 * slip (random and biased), quantised encoders and a MEMS IMU with noise, bias and bias random walk; the paper's
 * scenarios (Bernoulli lemniscate, circle, square with stops, start offset, point stabilization). The
 * {@code ./sabot simulate} command line with its CSV and PNG output is {@code sabot.tools.simulate.SimulateCommand}
 * (tools/sabot.tools).
 * <p>
 * Every random draw comes from generators seeded from {@link sabot.motion.sim.SimulationConfig#seed()}: the same
 * configuration gives bit-identical results.
 */
package sabot.motion.sim;
