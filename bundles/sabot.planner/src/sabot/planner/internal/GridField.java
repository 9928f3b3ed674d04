package sabot.planner.internal;

import sabot.model.geometry.Point2D;
import sabot.model.map.GridGeometry;
import sabot.planner.PotentialField;

/**
 * A {@link PotentialField} over a padded array of value bits (see {@link PlanningGrid} for the layout and
 * {@link LpnNavigationFunction#decode} for the encoding), either a live view of a planner's buffer or a snapshot.
 * Also holds the interpolation the path extraction descends.
 */
public final class GridField implements PotentialField {

    private final GridGeometry geometry;
    private final int stride;
    private final int[] values;
    private final int reached;

    GridField(GridGeometry geometry, int[] values, int reached) {
        this.geometry = geometry;
        this.stride = geometry.width() + 2;
        this.values = values;
        this.reached = reached;
    }

    @Override
    public GridGeometry geometry() {
        return geometry;
    }

    @Override
    public double value(int column, int row) {
        if (!geometry.contains(column, row)) {
            return Double.POSITIVE_INFINITY;
        }
        return LpnNavigationFunction.decode(values[(row + 1) * stride + column + 1]);
    }

    @Override
    public double valueAt(Point2D point) {
        if (point == null || !point.isFinite()) {
            return Double.POSITIVE_INFINITY;
        }
        double gx = geometry.toGridX(point.x());
        double gy = geometry.toGridY(point.y());
        if (!(gx >= 0 && gx < geometry.width() && gy >= 0 && gy < geometry.height())) {
            return Double.POSITIVE_INFINITY;
        }
        return interpolate(values, stride, gx, gy);
    }

    @Override
    public int reachedCells() {
        return reached;
    }

    @Override
    public PotentialField snapshot() {
        return new GridField(geometry, values.clone(), reached);
    }

    /**
     * Cost to goal at grid coordinates (cell (c, r) spans [c, c+1) x [r, r+1)), which must lie inside the grid:
     * 0 in a goal cell; bilinear between the four surrounding cell centres when all are reached; else the value of
     * the cell holding the point.
     */
    static double interpolate(int[] values, int stride, double gx, double gy) {
        int column = (int) gx;
        int row = (int) gy;
        float own = LpnNavigationFunction.decode(values[(row + 1) * stride + column + 1]);
        if (own == 0f || own == Float.POSITIVE_INFINITY) {
            return own;
        }
        double u = gx - 0.5;
        double v = gy - 0.5;
        int c0 = (int) Math.floor(u);
        int r0 = (int) Math.floor(v);
        double fu = u - c0;
        double fv = v - r0;
        int i00 = (r0 + 1) * stride + c0 + 1;
        float n00 = LpnNavigationFunction.decode(values[i00]);
        float n10 = LpnNavigationFunction.decode(values[i00 + 1]);
        float n01 = LpnNavigationFunction.decode(values[i00 + stride]);
        float n11 = LpnNavigationFunction.decode(values[i00 + stride + 1]);
        if (n00 == Float.POSITIVE_INFINITY || n10 == Float.POSITIVE_INFINITY || n01 == Float.POSITIVE_INFINITY
                || n11 == Float.POSITIVE_INFINITY) {
            return own;
        }
        return (1 - fv) * ((1 - fu) * n00 + fu * n10) + fv * ((1 - fu) * n01 + fu * n11);
    }
}
