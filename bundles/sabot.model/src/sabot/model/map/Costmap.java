package sabot.model.map;

import java.util.Arrays;

/**
 * The cost of being in each cell, as planners read it, in the ROS {@code costmap_2d} convention (one unsigned byte
 * per cell): {@value #FREE} free, 1..252 graded cost (higher is closer to an obstacle or otherwise less wanted),
 * {@value #INSCRIBED} within the robot's inscribed radius of an obstacle (the robot's centre may not be there),
 * {@value #LETHAL} an obstacle, {@value #NO_INFORMATION} unknown. Source of the values: ROS
 * {@code costmap_2d/cost_values.h}.
 *
 * <p>Cells are stored row-major with row 0 at the bottom of the map (see {@link GridGeometry}). Every change bumps a
 * {@linkplain #version() version} and remembers the changed block, so a consumer that keeps derived data (a planner's
 * padded copy, a rendered image) updates only {@link #changedSince(long) what changed}. Mutable, not thread-safe.
 */
public final class Costmap {

    /** Free space. */
    public static final int FREE = 0;
    /** Highest graded (passable) cost. */
    public static final int MAX_GRADED = 252;
    /** The robot's centre here would put its body in an obstacle: impassable. */
    public static final int INSCRIBED = 253;
    /** An obstacle: impassable. */
    public static final int LETHAL = 254;
    /** Nothing is known about the cell. */
    public static final int NO_INFORMATION = 255;

    /** How many recent changes are remembered one by one; older versions get the whole map as "changed". */
    private static final int CHANGE_LOG_SIZE = 64;

    private final GridGeometry geometry;
    private final byte[] costs;
    private long version;
    private final long[] changeVersions = new long[CHANGE_LOG_SIZE];
    private final CellRegion[] changeRegions = new CellRegion[CHANGE_LOG_SIZE];

    private Costmap(GridGeometry geometry, byte[] costs) {
        this.geometry = geometry;
        this.costs = costs;
        Arrays.fill(changeVersions, -1);
    }

    /** @return a costmap of the given geometry whose cells all hold {@code cost} (0..255) */
    public static Costmap filled(GridGeometry geometry, int cost) {
        checkCost(cost);
        byte[] costs = new byte[geometry.cellCount()];
        Arrays.fill(costs, (byte) cost);
        return new Costmap(geometry, costs);
    }

    /**
     * @param geometry size and placement
     * @param costs    row-major costs (row 0 at the bottom), unsigned bytes; copied
     * @throws IllegalArgumentException when the array length does not match the geometry
     */
    public static Costmap of(GridGeometry geometry, byte[] costs) {
        geometry.checkCellCount("costs", costs.length);
        return new Costmap(geometry, costs.clone());
    }

    /** @return size and placement */
    public GridGeometry geometry() {
        return geometry;
    }

    /** @return number of columns */
    public int width() {
        return geometry.width();
    }

    /** @return number of rows */
    public int height() {
        return geometry.height();
    }

    /** @return metres per cell edge */
    public double resolution() {
        return geometry.resolution();
    }

    /** @return the cost of a cell, 0..255 */
    public int cost(int column, int row) {
        return costs[geometry.checkedIndex(column, row)] & 0xFF;
    }

    /** @return the cost of the cell at a row-major index, 0..255 */
    public int costAt(int index) {
        return costs[index] & 0xFF;
    }

    /** @return true when the cost makes a cell impassable for the robot's centre (inscribed or lethal) */
    public static boolean isObstacle(int cost) {
        return cost == INSCRIBED || cost == LETHAL;
    }

    /** Sets one cell's cost (0..255). */
    public void set(int column, int row, int cost) {
        int index = geometry.checkedIndex(column, row);
        checkCost(cost);
        costs[index] = (byte) cost;
        recordChange(CellRegion.of(column, row));
    }

    /** Sets every cell of a region (clipped to the grid) to {@code cost} (0..255). */
    public void fill(CellRegion region, int cost) {
        checkCost(cost);
        CellRegion clipped = region.clip(width(), height());
        if (clipped.isEmpty()) {
            return;
        }
        for (int row = clipped.minRow(); row <= clipped.maxRow(); row++) {
            int base = row * width();
            Arrays.fill(costs, base + clipped.minColumn(), base + clipped.maxColumn() + 1, (byte) cost);
        }
        recordChange(clipped);
    }

    /**
     * Copies a block of cells from a full-size row-major array (same layout as this costmap) and records the block
     * as changed once; the cheap way to publish the result of a regional recomputation.
     */
    public void copyFrom(byte[] source, CellRegion region) {
        geometry.checkCellCount("costs", source.length);
        CellRegion clipped = region.clip(width(), height());
        if (clipped.isEmpty()) {
            return;
        }
        int span = clipped.maxColumn() - clipped.minColumn() + 1;
        for (int row = clipped.minRow(); row <= clipped.maxRow(); row++) {
            int start = row * width() + clipped.minColumn();
            System.arraycopy(source, start, costs, start, span);
        }
        recordChange(clipped);
    }

    /**
     * Copies part of one row into {@code destination} as unsigned bytes; no bounds beyond the arrays' own are checked
     * on the destination.
     */
    public void copyRow(int row, int fromColumn, int toColumnInclusive, byte[] destination, int destinationOffset) {
        int from = geometry.checkedIndex(fromColumn, row);
        geometry.checkedIndex(toColumnInclusive, row);
        System.arraycopy(costs, from, destination, destinationOffset,
                toColumnInclusive - fromColumn + 1);
    }

    /** @return a copy of all costs, row-major, row 0 at the bottom */
    public byte[] toArray() {
        return costs.clone();
    }

    /** @return an independent copy (version history not copied; the copy starts at version 0) */
    public Costmap copy() {
        return new Costmap(geometry, costs.clone());
    }

    /** @return a counter that grows with every change; 0 for a new costmap */
    public long version() {
        return version;
    }

    /**
     * @param sinceVersion a value {@link #version()} returned earlier
     * @return the smallest block holding every cell changed after that version: empty when nothing changed, the whole
     *         grid when the version is too old to be remembered (or is not one this costmap returned)
     */
    public CellRegion changedSince(long sinceVersion) {
        if (sinceVersion == version) {
            return CellRegion.EMPTY;
        }
        if (sinceVersion > version || sinceVersion < version - CHANGE_LOG_SIZE || sinceVersion < 0) {
            return geometry.bounds();
        }
        CellRegion changed = CellRegion.EMPTY;
        for (long v = sinceVersion + 1; v <= version; v++) {
            int slot = (int) (v % CHANGE_LOG_SIZE);
            if (changeVersions[slot] != v) {
                return geometry.bounds();
            }
            changed = changed.union(changeRegions[slot]);
        }
        return changed;
    }

    private void recordChange(CellRegion region) {
        version++;
        int slot = (int) (version % CHANGE_LOG_SIZE);
        changeVersions[slot] = version;
        changeRegions[slot] = region;
    }

    private static void checkCost(int cost) {
        if (cost < 0 || cost > 255) {
            throw new IllegalArgumentException("cost must be 0..255, got " + cost);
        }
    }
}
