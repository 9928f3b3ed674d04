package sabot.planner.internal;

import sabot.model.map.CellRegion;
import sabot.model.map.Costmap;
import sabot.model.map.GridGeometry;

/**
 * A planner's own copy of a costmap with a one-cell border of lethal cells around it, so that the hot loops reach all
 * eight neighbours of any cell by a fixed index offset without bounds checks. Kept in step with the costmap by copying
 * only the cells that changed since the last {@link #sync}.
 *
 * <p>Padded index of cell (column, row): {@code (row + 1) * stride + column + 1}.
 */
public final class PlanningGrid {

    /** Longest run of free cells {@link #freeRuns} counts. */
    public static final int MAX_FREE_RUN = 64;

    private Costmap source;
    private long sourceVersion;
    private GridGeometry geometry;
    private int stride;
    private byte[] costs = new byte[0];
    private byte[] freeRuns = new byte[0];
    private byte[] previous = new byte[0];
    private CellRegion previousRegion = CellRegion.EMPTY;

    /**
     * Brings the copy up to date with {@code costmap}.
     *
     * @return the cells that changed (unpadded coordinates): the whole grid the first time or after a geometry change,
     *         empty when nothing changed
     */
    public CellRegion sync(Costmap costmap) {
        CellRegion changed;
        if (costmap != source || !costmap.geometry().equals(geometry)) {
            geometry = costmap.geometry();
            stride = geometry.width() + 2;
            int padded = stride * (geometry.height() + 2);
            if (costs.length != padded) {
                costs = new byte[padded];
                freeRuns = new byte[padded];
            }
            java.util.Arrays.fill(costs, (byte) Costmap.LETHAL);
            java.util.Arrays.fill(freeRuns, (byte) 0); // the ring's runs, which are never recounted
            changed = geometry.bounds();
        } else {
            changed = costmap.changedSince(sourceVersion);
        }
        source = costmap;
        sourceVersion = costmap.version();
        previousRegion = changed;
        int span = changed.maxColumn() - changed.minColumn() + 1;
        if (!changed.isEmpty() && changed.cellCount() <= costs.length / 4) {
            if (previous.length < changed.cellCount()) {
                previous = new byte[(int) changed.cellCount()];
            }
            for (int row = changed.minRow(); row <= changed.maxRow(); row++) {
                System.arraycopy(costs, index(changed.minColumn(), row), previous,
                        (row - changed.minRow()) * span, span);
            }
        } else {
            previousRegion = CellRegion.EMPTY;
        }
        for (int row = changed.minRow(); row <= changed.maxRow(); row++) {
            costmap.copyRow(row, changed.minColumn(), changed.maxColumn(), costs, index(changed.minColumn(), row));
            countFreeRuns(row, changed.minColumn(), changed.maxColumn());
        }
        return changed;
    }

    /**
     * Recounts {@link #freeRuns} of a row from {@code maxColumn} leftwards: the cells of the changed columns and the
     * {@value #MAX_FREE_RUN} to their left, whose runs may reach into them.
     */
    private void countFreeRuns(int row, int minColumn, int maxColumn) {
        int from = index(maxColumn, row);
        int to = index(Math.max(-1, minColumn - MAX_FREE_RUN), row);
        int next = freeRuns[from + 1];
        for (int i = from; i >= to; i--) {
            next = costs[i] == Costmap.FREE ? Math.min(MAX_FREE_RUN, next + 1) : 0;
            freeRuns[i] = (byte) next;
        }
    }

    /**
     * @return the cost (0..255) a cell of the region changed by the last {@link #sync} had before it, or -1 when the
     *         cell is outside that region or the change was too large to be remembered
     */
    public int previousCost(int column, int row) {
        if (!previousRegion.contains(column, row)) {
            return -1;
        }
        int span = previousRegion.maxColumn() - previousRegion.minColumn() + 1;
        return previous[(row - previousRegion.minRow()) * span + column - previousRegion.minColumn()] & 0xFF;
    }

    /** @return the geometry of the costmap last synced */
    public GridGeometry geometry() {
        return geometry;
    }

    /** @return padded row length: width + 2 */
    public int stride() {
        return stride;
    }

    /** @return padded cell count: (width + 2) * (height + 2) */
    public int paddedSize() {
        return costs.length;
    }

    /** @return the padded cost array (unsigned bytes); read-only for callers */
    public byte[] costs() {
        return costs;
    }

    /**
     * @return by padded index, the number of free cells (cost {@link Costmap#FREE}) from that cell rightwards in its row,
     *         up to {@value #MAX_FREE_RUN}: a box of cells is all free when the run at its left edge covers its width in
     *         each of its rows; read-only for callers
     */
    public byte[] freeRuns() {
        return freeRuns;
    }

    /** @return padded index of an in-grid cell */
    public int index(int column, int row) {
        return (row + 1) * stride + column + 1;
    }

    /** @return column of a padded index (-1 or width on the border) */
    public int column(int index) {
        return index % stride - 1;
    }

    /** @return row of a padded index (-1 or height on the border) */
    public int row(int index) {
        return index / stride - 1;
    }
}
