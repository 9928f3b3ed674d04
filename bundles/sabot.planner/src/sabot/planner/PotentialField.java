package sabot.planner;

import org.osgi.annotation.versioning.ProviderType;

import sabot.model.geometry.Point2D;
import sabot.model.map.GridGeometry;

/**
 * A planner's cost-to-goal over the grid: 0 on goal cells, the least path cost (navfn cost units) to the goal set
 * elsewhere, {@code +infinity} where the goal cannot be reached from (obstacles, enclosed areas, cells a planner did
 * not need to visit).
 *
 * <p>A field returned by a planner is a view of that planner's buffers: it is valid until the same planner instance
 * plans again. Take a {@link #snapshot()} to keep it longer.
 */
@ProviderType
public interface PotentialField {

    /** @return size and placement of the grid the field covers */
    GridGeometry geometry();

    /** @return cost to goal of a cell in navfn cost units, {@code +infinity} when not reached */
    double value(int column, int row);

    /**
     * @return cost to goal at a map-frame point (metres), interpolated between cell centres when every cell around
     *         the point has a finite value, else the value of the cell holding it; 0 inside a goal cell;
     *         {@code +infinity} outside the grid or at unreached cells
     */
    double valueAt(Point2D point);

    /** @return how many cells have a finite value */
    int reachedCells();

    /** @return an independent copy that later planning does not change */
    PotentialField snapshot();
}
