package sabot.model.map;

import java.util.Optional;

import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;

/**
 * Size and placement of a grid in the map frame.
 *
 * <p>The cell (c, r) covers {@code [origin.x + c*resolution, origin.x + (c+1)*resolution)} along x and likewise
 * along y. Like ROS {@code map_server}, the origin's heading is carried along but not applied: grids are axis-aligned.
 *
 * @param width      number of columns, at least 1
 * @param height     number of rows, at least 1
 * @param resolution edge length of a cell in metres, finite and positive
 * @param origin     map-frame pose of the lower-left corner of cell (0, 0); metres and radians
 */
public record GridGeometry(int width, int height, double resolution, Pose2D origin) {

    /** Largest number of cells of one grid: arrays are indexed by int. */
    public static final long MAX_CELLS = Integer.MAX_VALUE - 16;

    /** @throws IllegalArgumentException naming the offending field when the geometry is unusable */
    public GridGeometry {
        if (width <= 0 || height <= 0) {
            throw new IllegalArgumentException("grid must have at least one cell, got " + width + " x " + height);
        }
        if ((long) width * height > MAX_CELLS) {
            throw new IllegalArgumentException("grid of " + width + " x " + height + " cells is too large");
        }
        if (!(resolution > 0) || !Double.isFinite(resolution)) {
            throw new IllegalArgumentException("resolution must be a positive number of metres, got " + resolution);
        }
        if (origin == null || !origin.isFinite()) {
            throw new IllegalArgumentException("origin must be a finite pose, got " + origin);
        }
    }

    /** @return width * height */
    public int cellCount() {
        return width * height;
    }

    /** @return true when the cell lies in the grid */
    public boolean contains(int column, int row) {
        return column >= 0 && column < width && row >= 0 && row < height;
    }

    /** @return the row-major index of a cell ({@code row * width + column}); the cell must be inside */
    public int index(int column, int row) {
        return row * width + column;
    }

    /**
     * @return the row-major index of a cell
     * @throws IndexOutOfBoundsException naming the cell and the grid's size when the cell is outside
     */
    public int checkedIndex(int column, int row) {
        if (!contains(column, row)) {
            throw new IndexOutOfBoundsException("cell (" + column + ", " + row + ") is outside the " + width + " x "
                    + height + " grid");
        }
        return index(column, row);
    }

    /**
     * Checks that an array of per-cell values fits this grid.
     *
     * @param what   what the values are, for the message (e.g. "costs")
     * @param length the array's length
     * @throws IllegalArgumentException when it is not {@link #cellCount()}
     */
    public void checkCellCount(String what, int length) {
        if (length != cellCount()) {
            throw new IllegalArgumentException("expected " + cellCount() + " " + what + " for a " + width + " x "
                    + height + " grid, got " + length);
        }
    }

    /** @return the cell holding a map-frame point, or empty when the point is outside the grid or not finite */
    public Optional<Cell> cellAt(Point2D point) {
        if (point == null || !point.isFinite()) {
            return Optional.empty();
        }
        double gx = toGridX(point.x());
        double gy = toGridY(point.y());
        if (!(gx >= 0 && gx < width && gy >= 0 && gy < height)) {
            return Optional.empty();
        }
        return Optional.of(new Cell((int) gx, (int) gy));
    }

    /** @return a map-frame x in metres as a fractional column (cell c spans [c, c+1)) */
    public double toGridX(double x) {
        return (x - origin.x()) / resolution;
    }

    /** @return a map-frame y in metres as a fractional row (cell r spans [r, r+1)) */
    public double toGridY(double y) {
        return (y - origin.y()) / resolution;
    }

    /** @return the map-frame point, in metres, of fractional grid coordinates */
    public Point2D toMap(double gridX, double gridY) {
        return new Point2D(origin.x() + gridX * resolution, origin.y() + gridY * resolution);
    }

    /** @return the map-frame centre of a cell, in metres */
    public Point2D cellCentre(int column, int row) {
        return toMap(column + 0.5, row + 0.5);
    }

    /** @return the whole grid as a region */
    public CellRegion bounds() {
        return new CellRegion(0, 0, width - 1, height - 1);
    }
}
