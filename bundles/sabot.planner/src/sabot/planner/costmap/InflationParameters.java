package sabot.planner.costmap;

/**
 * How obstacles spread cost, after ROS {@code costmap_2d}'s inflation layer ({@code inflation_layer.h},
 * {@code computeCost}): a cell at distance d (metres, centre to centre) from the nearest lethal cell costs
 *
 * <pre>
 *   254 (lethal)                                        d = 0
 *   253 (inscribed)                                     0 &lt; d &lt;= inscribedRadius
 *   252 * exp(-costScalingFactor * (d - inscribedRadius))   inscribedRadius &lt; d &lt;= inflationRadius
 *   0                                                  beyond
 * </pre>
 *
 * @param inscribedRadius   metres: radius of the largest circle inside the robot's footprint; the robot's centre may
 *                          not come closer to an obstacle
 * @param inflationRadius   metres, at least {@code inscribedRadius}: how far cost spreads
 * @param costScalingFactor per metre, positive: how fast the cost decays beyond the inscribed radius
 * @param lethalThreshold   occupancy (0..100) from which an occupancy-grid cell is an obstacle ({@code costmap_2d}
 *                          static layer default 100)
 * @param unknownCells      what unknown occupancy-grid cells become
 */
public record InflationParameters(double inscribedRadius, double inflationRadius, double costScalingFactor,
        int lethalThreshold, UnknownCellPolicy unknownCells) {

    /** costmap_2d's default {@code inflation_radius}, metres. */
    public static final double DEFAULT_INFLATION_RADIUS = 0.55;
    /** costmap_2d's default {@code cost_scaling_factor}, per metre. */
    public static final double DEFAULT_COST_SCALING_FACTOR = 10.0;
    /** costmap_2d's static-layer default {@code lethal_cost_threshold}, occupancy percent. */
    public static final int DEFAULT_LETHAL_THRESHOLD = 100;

    /** @throws IllegalArgumentException naming the parameter when a value is unusable */
    public InflationParameters {
        if (!(inscribedRadius >= 0) || !Double.isFinite(inscribedRadius)) {
            throw new IllegalArgumentException("inscribed radius must be >= 0 m, got " + inscribedRadius);
        }
        if (!(inflationRadius >= inscribedRadius) || !Double.isFinite(inflationRadius)) {
            throw new IllegalArgumentException("inflation radius must be >= the inscribed radius (" + inscribedRadius
                    + " m), got " + inflationRadius);
        }
        if (!(costScalingFactor > 0) || !Double.isFinite(costScalingFactor)) {
            throw new IllegalArgumentException("cost scaling factor must be > 0 per metre, got " + costScalingFactor);
        }
        if (lethalThreshold < 1 || lethalThreshold > 100) {
            throw new IllegalArgumentException("lethal threshold must be 1..100, got " + lethalThreshold);
        }
        if (unknownCells == null) {
            throw new IllegalArgumentException("unknown-cell policy is required");
        }
    }

    /** @return parameters for a robot of that inscribed radius (metres) with costmap_2d's other defaults */
    public static InflationParameters forRobot(double inscribedRadius) {
        return new InflationParameters(inscribedRadius, Math.max(inscribedRadius, DEFAULT_INFLATION_RADIUS),
                DEFAULT_COST_SCALING_FACTOR, DEFAULT_LETHAL_THRESHOLD, UnknownCellPolicy.KEEP_UNKNOWN);
    }

    /** @return a copy with another inflation radius and decay */
    public InflationParameters withDecay(double newInflationRadius, double newCostScalingFactor) {
        return new InflationParameters(inscribedRadius, newInflationRadius, newCostScalingFactor, lethalThreshold,
                unknownCells);
    }

    /** @return a copy with another unknown-cell policy */
    public InflationParameters withUnknownCells(UnknownCellPolicy policy) {
        return new InflationParameters(inscribedRadius, inflationRadius, costScalingFactor, lethalThreshold, policy);
    }

    /**
     * @param distance metres from the nearest lethal cell
     * @return the inflated cost 0..254 at that distance
     */
    public int costAt(double distance) {
        if (distance <= 0) {
            return 254;
        }
        if (distance <= inscribedRadius) {
            return 253;
        }
        if (distance > inflationRadius) {
            return 0;
        }
        return (int) (252 * Math.exp(-costScalingFactor * (distance - inscribedRadius)));
    }
}
