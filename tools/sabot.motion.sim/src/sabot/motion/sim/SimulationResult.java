package sabot.motion.sim;

import java.util.List;

import sabot.localization.OdometryCalibration;
import sabot.localization.calibration.SquareRunResult;

/**
 * What a simulation produced.
 *
 * @param config          the settings
 * @param trace           one row per control step (all runs of a stabilization scenario, told apart by "run")
 * @param metrics         the figures
 * @param odometryGeometry the wheel radii and track the odometry used
 * @param calibrationRuns the UMBmark runs when calibrated, else empty
 */
public record SimulationResult(SimulationConfig config, Trace trace, Metrics metrics,
        OdometryCalibration odometryGeometry, List<SquareRunResult> calibrationRuns) {
}
