package sabot.planner;

import java.util.List;

import sabot.model.geometry.Point2D;
import sabot.model.map.Costmap;
import sabot.model.map.GridGeometry;
import sabot.planner.internal.GridTraversal;

/**
 * The cost every Sabot planner minimises: the line integral of a cost density {@code h} along the path, with the path
 * measured in cell edges. A cell of costmap value {@code c} (0..252) has density
 * {@code h(c) = COST_NEUTRAL + COST_FACTOR * c}; inscribed and lethal cells are impassable, unknown cells are
 * impassable unless allowed, then they cost like the highest graded value. The constants are ROS navfn's
 * ({@code navfn/include/navfn/navfn.h}, K. Konolige, Willow Garage 2008), so costs compare with navfn's potentials.
 *
 * <p>On the grid, a step between neighbouring cell centres p and q costs {@code |p - q| * (h(p) + h(q)) / 2}: the
 * trapezoid rule of the line integral, exact for the straight segment between the centres (half of it lies in each
 * cell). Konolige's LPN paper (IROS 2000) writes the same cost as adjacency {@code A(q,p)} (here
 * {@code COST_NEUTRAL * |p - q|}) plus intrinsic {@code I(p)} (here {@code COST_FACTOR * c * |p - q|}, the
 * intrinsic cost scaled by the distance travelled in the cell, so that a diagonal step is no cheaper per metre).
 */
public final class CostModel {

    /** Density of free space, cost units per cell edge (navfn.h {@code COST_NEUTRAL}). */
    public static final float COST_NEUTRAL = 50f;
    /** Density added per unit of costmap value (navfn.h {@code COST_FACTOR}). */
    public static final float COST_FACTOR = 0.8f;

    private static final CostModel STANDARD = new CostModel(false);
    private static final CostModel ALLOWING_UNKNOWN = new CostModel(true);

    private final boolean unknownPassable;
    private final float[] densityByCost = new float[256];

    private CostModel(boolean unknownPassable) {
        this.unknownPassable = unknownPassable;
        for (int cost = 0; cost < 256; cost++) {
            densityByCost[cost] = cost <= Costmap.MAX_GRADED ? COST_NEUTRAL + COST_FACTOR * cost
                    : Float.POSITIVE_INFINITY;
        }
        if (unknownPassable) {
            densityByCost[Costmap.NO_INFORMATION] = COST_NEUTRAL + COST_FACTOR * Costmap.MAX_GRADED;
        }
    }

    /** @return the model where unknown cells are impassable (the default) */
    public static CostModel standard() {
        return STANDARD;
    }

    /** @return the model where unknown cells may be crossed at the highest graded cost */
    public static CostModel allowingUnknown() {
        return ALLOWING_UNKNOWN;
    }

    /** @return true when unknown cells are passable */
    public boolean unknownPassable() {
        return unknownPassable;
    }

    /** @return density of a costmap value 0..255 in cost units per cell edge; {@code +infinity} when impassable */
    public float density(int cost) {
        return densityByCost[cost];
    }

    /** @return true when the robot's centre may be in a cell of that costmap value */
    public boolean passable(int cost) {
        return densityByCost[cost] != Float.POSITIVE_INFINITY;
    }

    /** @return a copy of the density of every costmap value 0..255 (the planners' lookup table) */
    public float[] densityTable() {
        return densityByCost.clone();
    }

    /** @return the smallest density of a passable cell */
    public float minDensity() {
        return COST_NEUTRAL;
    }

    /** @return the largest density of a passable cell */
    public float maxDensity() {
        return COST_NEUTRAL + COST_FACTOR * Costmap.MAX_GRADED;
    }

    /**
     * @param waypoints map-frame polyline in metres
     * @return the line integral of the density along the polyline (length in cell edges), in cost units;
     *         {@code +infinity} when the polyline crosses an impassable cell or leaves the map
     */
    public double pathCost(Costmap costmap, List<Point2D> waypoints) {
        GridGeometry geometry = costmap.geometry();
        return GridTraversal.integrate(geometry, waypoints, (column, row) -> geometry.contains(column, row)
                ? densityByCost[costmap.cost(column, row)]
                : Double.POSITIVE_INFINITY);
    }

    /** @return the Euclidean length of a polyline in metres */
    public static double length(List<Point2D> waypoints) {
        double total = 0;
        for (int i = 1; i < waypoints.size(); i++) {
            total += waypoints.get(i - 1).distanceTo(waypoints.get(i));
        }
        return total;
    }
}
