package sabot.motion.sim;

import java.util.Locale;

/**
 * The figures of one simulation. NaN means "not applicable to this scenario" and is printed as JSON {@code null}.
 *
 * @param rmsError         RMS of |true position &minus; reference position| after the first 5 s of the reference, m
 * @param maxError         maximum of the same, m
 * @param returnError      closed scenarios: distance between the true start and the true end, m
 * @param finalError       tracking: distance between the true end and the reference's end; stabilization: the
 *                         largest final distance to the goal over all starts, m
 * @param finalHeadingError stabilization: largest final |heading &minus; goal heading| over all starts, rad
 * @param settleTime       first time (s after the reference starts) from which the error stays &le; 2 cm; NaN if never
 * @param estimateError    distance between the estimate and the truth at the end, m
 * @param limitViolations  control steps whose applied command broke a speed, wheel-speed or acceleration limit
 * @param nanCommands      control steps whose command had a NaN or infinite component
 * @param maxYawRate       largest |&omega;| applied, rad/s (a blow-up near &xi; = 0 would show here)
 */
public record Metrics(double rmsError, double maxError, double returnError, double finalError, double finalHeadingError,
        double settleTime, double estimateError, int limitViolations, int nanCommands, double maxYawRate) {

    /** @return one JSON object, keys as documented in docs/MOTION.md */
    public String toJson(SimulationConfig c) {
        return String.format(Locale.ROOT,
                "{\"scenario\":\"%s\",\"controller\":\"%s\",\"feedback\":\"%s\",\"seed\":%d,\"slip_noise\":%s,"
                        + "\"slip_bias\":%s,\"calibrated\":%s,\"rms_m\":%s,\"max_m\":%s,\"return_m\":%s,\"final_m\":%s,"
                        + "\"final_heading_rad\":%s,\"settle_s\":%s,\"estimate_error_m\":%s,\"limit_violations\":%d,"
                        + "\"nan_commands\":%d,\"max_yaw_rate_radps\":%s}",
                c.scenario().cliName(), c.controller().cliName(), c.feedback().cliName(), c.seed(), num(c.slipNoise()),
                num(c.slipBias()), c.calibrated(), num(rmsError), num(maxError), num(returnError), num(finalError),
                num(finalHeadingError), num(settleTime), num(estimateError), limitViolations, nanCommands,
                num(maxYawRate));
    }

    private static String num(double v) {
        return Double.isFinite(v) ? String.format(Locale.ROOT, "%.6g", v) : "null";
    }
}
