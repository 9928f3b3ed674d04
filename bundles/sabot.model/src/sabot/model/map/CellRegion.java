package sabot.model.map;

/**
 * An axis-aligned block of cells, bounds inclusive; used to name what changed in a grid so that consumers
 * update only that block.
 *
 * @param minColumn first column
 * @param minRow    first row
 * @param maxColumn last column (inclusive)
 * @param maxRow    last row (inclusive)
 */
public record CellRegion(int minColumn, int minRow, int maxColumn, int maxRow) {

    /** The empty region: contains no cell; the identity of {@link #union}. */
    public static final CellRegion EMPTY = new CellRegion(0, 0, -1, -1);

    /** @return a region holding one cell */
    public static CellRegion of(int column, int row) {
        return new CellRegion(column, row, column, row);
    }

    /** @return true when the region contains no cell */
    public boolean isEmpty() {
        return maxColumn < minColumn || maxRow < minRow;
    }

    /** @return the number of cells in the region */
    public long cellCount() {
        return isEmpty() ? 0 : (long) (maxColumn - minColumn + 1) * (maxRow - minRow + 1);
    }

    /** @return true when the cell lies in this region */
    public boolean contains(int column, int row) {
        return column >= minColumn && column <= maxColumn && row >= minRow && row <= maxRow;
    }

    /** @return the smallest region holding both */
    public CellRegion union(CellRegion other) {
        if (isEmpty()) {
            return other;
        }
        if (other.isEmpty()) {
            return this;
        }
        return new CellRegion(Math.min(minColumn, other.minColumn), Math.min(minRow, other.minRow),
                Math.max(maxColumn, other.maxColumn), Math.max(maxRow, other.maxRow));
    }

    /** @return this region grown by {@code cells} on every side (not clipped) */
    public CellRegion expand(int cells) {
        return isEmpty() ? this : new CellRegion(minColumn - cells, minRow - cells, maxColumn + cells, maxRow + cells);
    }

    /** @return the part of this region inside a {@code width} x {@code height} grid (possibly empty) */
    public CellRegion clip(int width, int height) {
        if (isEmpty()) {
            return this;
        }
        CellRegion clipped = new CellRegion(Math.max(0, minColumn), Math.max(0, minRow), Math.min(width - 1, maxColumn),
                Math.min(height - 1, maxRow));
        return clipped.isEmpty() ? EMPTY : clipped;
    }
}
