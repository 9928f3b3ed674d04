package sabot.planner.internal;

import java.util.List;

import sabot.model.geometry.Point2D;
import sabot.model.map.GridGeometry;

/**
 * Walks the cells a straight segment crosses, in grid coordinates (cell (c, r) spans [c, c+1) x [r, r+1)), after
 * Amanatides and Woo, "A fast voxel traversal algorithm for ray tracing", Eurographics 1987. A segment that passes
 * exactly through a cell corner steps diagonally: the two side cells are touched in a point only and do not count.
 */
public final class GridTraversal {

    /** Length in cell edges below which a piece of a segment inside a cell is treated as touching it in a point. */
    private static final double NEGLIGIBLE = 1e-9;

    /** Density of a cell; may be {@code +infinity}. */
    @FunctionalInterface
    public interface CellDensity {
        double at(int column, int row);
    }

    private GridTraversal() {
    }

    /**
     * @return the sum over the cells the segment crosses of (length inside the cell, cell edges) x density;
     *         {@code +infinity} as soon as a crossed cell has infinite density
     */
    public static double integrate(double x0, double y0, double x1, double y1, CellDensity density) {
        return integrate(x0, y0, x1, y1, density, Double.POSITIVE_INFINITY);
    }

    /**
     * @param polyline map-frame polyline in metres, on the grid of {@code geometry}
     * @return the sum of {@link #integrate(double, double, double, double, CellDensity)} over its segments: the line
     *         integral of the density along it in cost units, {@code +infinity} when it crosses an infinite density
     */
    public static double integrate(GridGeometry geometry, List<Point2D> polyline, CellDensity density) {
        double total = 0;
        for (int i = 1; i < polyline.size(); i++) {
            Point2D a = polyline.get(i - 1);
            Point2D b = polyline.get(i);
            total += integrate(geometry.toGridX(a.x()), geometry.toGridY(a.y()), geometry.toGridX(b.x()), geometry
                    .toGridY(b.y()), density);
        }
        return total;
    }

    /**
     * As {@link #integrate(double, double, double, double, CellDensity)}, but returns a partial sum above
     * {@code limit} as soon as the walk exceeds it (the pieces are not negative, so the whole sum would too).
     */
    public static double integrate(double x0, double y0, double x1, double y1, CellDensity density, double limit) {
        double dx = x1 - x0;
        double dy = y1 - y0;
        double length = Math.sqrt(dx * dx + dy * dy); // not Math.hypot: a software routine, no overflow to guard
        int column = (int) Math.floor(x0);
        int row = (int) Math.floor(y0);
        int lastColumn = (int) Math.floor(x1);
        int lastRow = (int) Math.floor(y1);
        if (length < NEGLIGIBLE) {
            double d = density.at(column, row);
            return d == Double.POSITIVE_INFINITY ? d : 0;
        }
        if (column == lastColumn && row == lastRow) {
            // inside one cell, as most of a descent's half-cell steps: what the walk below gives, bit for bit (its
            // one piece is (1 - 0) * length), without its four divisions
            return length > NEGLIGIBLE ? length * density.at(column, row) : 0;
        }
        int stepX = dx > 0 ? 1 : dx < 0 ? -1 : 0;
        int stepY = dy > 0 ? 1 : dy < 0 ? -1 : 0;
        double tDeltaX = stepX == 0 ? Double.POSITIVE_INFINITY : 1.0 / Math.abs(dx);
        double tDeltaY = stepY == 0 ? Double.POSITIVE_INFINITY : 1.0 / Math.abs(dy);
        double tMaxX = stepX == 0 ? Double.POSITIVE_INFINITY
                : ((stepX > 0 ? column + 1 - x0 : x0 - column) / Math.abs(dx));
        double tMaxY = stepY == 0 ? Double.POSITIVE_INFINITY
                : ((stepY > 0 ? row + 1 - y0 : y0 - row) / Math.abs(dy));
        double t = 0;
        double total = 0;
        int guard = Math.abs(lastColumn - column) + Math.abs(lastRow - row) + 2;
        while (guard-- > 0) {
            double tExit = Math.min(1.0, Math.min(tMaxX, tMaxY));
            double piece = (tExit - t) * length;
            if (piece > NEGLIGIBLE) {
                double d = density.at(column, row);
                if (d == Double.POSITIVE_INFINITY) {
                    return d;
                }
                total += piece * d;
                if (total > limit) {
                    return total;
                }
            }
            if (tExit >= 1.0 || column == lastColumn && row == lastRow) {
                break;
            }
            t = tExit;
            if (Math.abs(tMaxX - tMaxY) < NEGLIGIBLE) {
                column += stepX;
                row += stepY;
                tMaxX += tDeltaX;
                tMaxY += tDeltaY;
            } else if (tMaxX < tMaxY) {
                column += stepX;
                tMaxX += tDeltaX;
            } else {
                row += stepY;
                tMaxY += tDeltaY;
            }
        }
        return total;
    }

    /**
     * Density of the cells of a {@link PlanningGrid}'s padded copy: +infinity outside the grid's padding ring (the
     * ring itself is lethal), as for a costmap's cells outside the map. A final class: with the cost model's lambda
     * (CostModel.pathCost) the walk's density call sees two types and is inlined for both (it saw several lambdas
     * before, megamorphic: each cell a virtual call).
     */
    static final class PaddedDensity implements CellDensity {
        private final byte[] costs;
        private final float[] density;
        private final int stride;
        private final int width;
        private final int height;

        PaddedDensity(PlanningGrid grid, float[] density) {
            this.costs = grid.costs();
            this.density = density;
            this.stride = grid.stride();
            this.width = grid.geometry().width();
            this.height = grid.geometry().height();
        }

        @Override
        public double at(int column, int row) {
            if (column < -1 || row < -1 || column > width || row > height) {
                return Double.POSITIVE_INFINITY;
            }
            return density[costs[(row + 1) * stride + column + 1] & 0xFF];
        }
    }
}
