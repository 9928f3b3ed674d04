package sabot.model.map;

import java.util.Arrays;

import sabot.model.geometry.Pose2D;

/**
 * What is known about the space around the robot, one value per cell, in the ROS {@code nav_msgs/OccupancyGrid}
 * convention: {@value #UNKNOWN} for unknown, 0 for certainly free up to {@value #OCCUPIED} for certainly occupied.
 *
 * <p>Cells are stored row-major with row 0 at the bottom of the map (see {@link GridGeometry}). The grid is mutable
 * and not thread-safe.
 */
public final class OccupancyGrid {

    /** Value of a cell nothing is known about. */
    public static final byte UNKNOWN = -1;
    /** Value of a certainly free cell. */
    public static final byte FREE = 0;
    /** Value of a certainly occupied cell. */
    public static final byte OCCUPIED = 100;

    private final GridGeometry geometry;
    private final byte[] values;

    private OccupancyGrid(GridGeometry geometry, byte[] values) {
        this.geometry = geometry;
        this.values = values;
    }

    /**
     * @param width      columns, at least 1
     * @param height     rows, at least 1
     * @param resolution metres per cell edge, positive
     * @param origin     map-frame pose of the grid's lower-left corner
     * @return a grid whose cells are all {@link #UNKNOWN}
     * @throws IllegalArgumentException naming the problem when the geometry is unusable
     */
    public static OccupancyGrid unknown(int width, int height, double resolution, Pose2D origin) {
        GridGeometry geometry = new GridGeometry(width, height, resolution, origin);
        byte[] values = new byte[geometry.cellCount()];
        Arrays.fill(values, UNKNOWN);
        return new OccupancyGrid(geometry, values);
    }

    /**
     * @param geometry size and placement
     * @param values   row-major cell values (row 0 at the bottom), each -1 or 0..100; copied
     * @throws IllegalArgumentException when the array length does not match or a value is out of range
     */
    public static OccupancyGrid of(GridGeometry geometry, byte[] values) {
        geometry.checkCellCount("cell values", values.length);
        for (int i = 0; i < values.length; i++) {
            checkValue(values[i]);
        }
        return new OccupancyGrid(geometry, values.clone());
    }

    /** @return size and placement of the grid */
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

    /** @return the value of a cell: -1 unknown, 0..100 occupancy in percent */
    public int get(int column, int row) {
        return values[geometry.checkedIndex(column, row)];
    }

    /** Sets a cell to -1 (unknown) or an occupancy 0..100 in percent. */
    public void set(int column, int row, int value) {
        int index = geometry.checkedIndex(column, row);
        checkValue(value);
        values[index] = (byte) value;
    }

    /** @return a copy of all values, row-major, row 0 at the bottom */
    public byte[] toArray() {
        return values.clone();
    }

    /** @return true when both grids have the same geometry and values */
    public boolean sameAs(OccupancyGrid other) {
        return geometry.equals(other.geometry) && Arrays.equals(values, other.values);
    }

    private static void checkValue(int value) {
        if (value < UNKNOWN || value > OCCUPIED) {
            throw new IllegalArgumentException("occupancy must be -1 (unknown) or 0..100, got " + value);
        }
    }
}
