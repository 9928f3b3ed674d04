package sabot.planner.costmap;

import java.util.Arrays;
import java.util.List;

import sabot.model.geometry.Point2D;
import sabot.model.map.Cell;
import sabot.model.map.CellRegion;
import sabot.model.map.Costmap;
import sabot.model.map.GridGeometry;
import sabot.model.map.OccupancyGrid;

/**
 * Keeps the layers a costmap is made of and publishes their combination into one {@link Costmap}:
 * <ol>
 * <li>obstacles: free, lethal or unknown per cell (from an occupancy grid, then from sensors);</li>
 * <li>inflation: obstacles spread by {@link InflationParameters};</li>
 * <li>moving obstacles: the space they are about to sweep ({@link MovingObstacleModel}).</li>
 * </ol>
 * The published cost is the inflated cost, raised to the moving-obstacle cost where that is higher, except that
 * impassable and unknown cells stay what they are. Every change recomputes only the cells it can affect: a changed
 * obstacle cell affects cells within the inflation radius, which depend on obstacles within twice that radius; the
 * costmap's {@link Costmap#changedSince change tracking} then lets planners copy only those cells. Not thread-safe.
 */
public final class CostmapLayers {

    private final GridGeometry geometry;
    private final InflationParameters inflation;
    private final MovingObstacleModel movingModel;
    private final byte[] obstacles;
    private final byte[] inflated;
    private final byte[] moving;
    private final byte[] composite;
    private final Costmap costmap;
    private final int kernelRadius;
    private final int[] kernelDx;
    private final int[] kernelDy;
    private final byte[] kernelCost;
    private CellRegion movingRegion = CellRegion.EMPTY;

    private CostmapLayers(GridGeometry geometry, byte[] obstacles, InflationParameters inflation,
            MovingObstacleModel movingModel) {
        this.geometry = geometry;
        this.inflation = inflation;
        this.movingModel = movingModel;
        this.obstacles = obstacles;
        int cells = geometry.cellCount();
        this.inflated = new byte[cells];
        this.moving = new byte[cells];
        this.composite = new byte[cells];
        this.kernelRadius = (int) Math.ceil(inflation.inflationRadius() / geometry.resolution());
        int side = 2 * kernelRadius + 1;
        int[] dx = new int[side * side];
        int[] dy = new int[side * side];
        byte[] cost = new byte[side * side];
        int count = 0;
        for (int j = -kernelRadius; j <= kernelRadius; j++) {
            for (int i = -kernelRadius; i <= kernelRadius; i++) {
                int c = inflation.costAt(Math.hypot(i, j) * geometry.resolution());
                if (c > 0 && (i != 0 || j != 0)) {
                    dx[count] = i;
                    dy[count] = j;
                    cost[count++] = (byte) c;
                }
            }
        }
        this.kernelDx = Arrays.copyOf(dx, count);
        this.kernelDy = Arrays.copyOf(dy, count);
        this.kernelCost = Arrays.copyOf(cost, count);
        recomputeInflation(geometry.bounds());
        combine(geometry.bounds());
        this.costmap = Costmap.of(geometry, composite);
    }

    /**
     * @param grid  the map; cells at or above the lethal threshold become obstacles, unknown cells follow the
     *              unknown-cell policy, all others are free
     * @param model how moving obstacles spread cost
     */
    public static CostmapLayers fromOccupancy(OccupancyGrid grid, InflationParameters inflation,
            MovingObstacleModel model) {
        byte[] values = grid.toArray();
        byte[] obstacles = new byte[values.length];
        for (int i = 0; i < values.length; i++) {
            int v = values[i];
            int cost;
            if (v == OccupancyGrid.UNKNOWN) {
                cost = switch (inflation.unknownCells()) {
                    case FREE -> Costmap.FREE;
                    case LETHAL -> Costmap.LETHAL;
                    case KEEP_UNKNOWN -> Costmap.NO_INFORMATION;
                };
            } else {
                cost = v >= inflation.lethalThreshold() ? Costmap.LETHAL : Costmap.FREE;
            }
            obstacles[i] = (byte) cost;
        }
        return new CostmapLayers(grid.geometry(), obstacles, inflation, model);
    }

    /** @return layers over an all-free map of that geometry */
    public static CostmapLayers free(GridGeometry geometry, InflationParameters inflation, MovingObstacleModel model) {
        return new CostmapLayers(geometry, new byte[geometry.cellCount()], inflation, model);
    }

    /** @return the published costmap; it changes in place with every update */
    public Costmap costmap() {
        return costmap;
    }

    /** @return size and placement */
    public GridGeometry geometry() {
        return geometry;
    }

    /**
     * Marks the cell holding a map-frame point (metres) as an obstacle, e.g. a sonar return.
     *
     * @return false when the point is outside the map (nothing changes)
     */
    public boolean markObstacle(Point2D point) {
        java.util.Optional<Cell> cell = geometry.cellAt(point);
        cell.ifPresent(c -> setObstacles(CellRegion.of(c.column(), c.row()), Costmap.LETHAL));
        return cell.isPresent();
    }

    /**
     * Sets the obstacle layer of a block of cells (clipped to the map) and updates inflation and costmap around it.
     *
     * @param value {@link Costmap#FREE}, {@link Costmap#LETHAL} or {@link Costmap#NO_INFORMATION}
     * @return the block of costmap cells that was recomputed
     */
    public CellRegion setObstacles(CellRegion region, int value) {
        if (value != Costmap.FREE && value != Costmap.LETHAL && value != Costmap.NO_INFORMATION) {
            throw new IllegalArgumentException("obstacle layer holds FREE, LETHAL or NO_INFORMATION, got " + value);
        }
        CellRegion clipped = region.clip(geometry.width(), geometry.height());
        if (clipped.isEmpty()) {
            return clipped;
        }
        for (int row = clipped.minRow(); row <= clipped.maxRow(); row++) {
            int base = row * geometry.width();
            Arrays.fill(obstacles, base + clipped.minColumn(), base + clipped.maxColumn() + 1, (byte) value);
        }
        CellRegion affected = clipped.expand(kernelRadius).clip(geometry.width(), geometry.height());
        recomputeInflation(affected);
        publish(affected);
        return affected;
    }

    /**
     * Replaces the moving obstacles; the cells their previous prediction covered and the cells the new one covers
     * are recomputed, nothing else.
     *
     * @param robotVx the robot's map-frame velocity along x, m/s (for the closing speed)
     * @param robotVy the robot's map-frame velocity along y, m/s
     * @return the block of costmap cells that was recomputed
     */
    public CellRegion setMovingObstacles(List<MovingObstacle> movingObstacles, double robotVx, double robotVy) {
        CellRegion previous = movingRegion;
        clearRegion(moving, previous);
        CellRegion swept = CellRegion.EMPTY;
        for (MovingObstacle obstacle : movingObstacles) {
            CellRegion box = sweptBox(obstacle);
            swept = swept.union(box);
            for (int row = box.minRow(); row <= box.maxRow(); row++) {
                for (int column = box.minColumn(); column <= box.maxColumn(); column++) {
                    Point2D centre = geometry.cellCentre(column, row);
                    int cost = movingModel.cost(obstacle, centre.x(), centre.y(), robotVx, robotVy);
                    int index = row * geometry.width() + column;
                    if (cost > (moving[index] & 0xFF)) {
                        moving[index] = (byte) cost;
                    }
                }
            }
        }
        movingRegion = swept;
        CellRegion affected = previous.union(swept);
        publish(affected);
        return affected;
    }

    private CellRegion sweptBox(MovingObstacle obstacle) {
        double reach = movingModel.lateralReach(obstacle);
        double x0 = obstacle.position().x();
        double y0 = obstacle.position().y();
        double x1 = x0 + obstacle.vx() * movingModel.horizon();
        double y1 = y0 + obstacle.vy() * movingModel.horizon();
        int minColumn = (int) Math.floor(geometry.toGridX(Math.min(x0, x1) - reach));
        int maxColumn = (int) Math.floor(geometry.toGridX(Math.max(x0, x1) + reach));
        int minRow = (int) Math.floor(geometry.toGridY(Math.min(y0, y1) - reach));
        int maxRow = (int) Math.floor(geometry.toGridY(Math.max(y0, y1) + reach));
        return new CellRegion(minColumn, minRow, maxColumn, maxRow).clip(geometry.width(), geometry.height());
    }

    private void recomputeInflation(CellRegion affected) {
        int width = geometry.width();
        for (int row = affected.minRow(); row <= affected.maxRow(); row++) {
            int base = row * width;
            for (int column = affected.minColumn(); column <= affected.maxColumn(); column++) {
                inflated[base + column] = obstacles[base + column];
            }
        }
        // the nearest lethal cell of any cell is a boundary cell (one with a non-lethal 4-neighbour), so only
        // boundary cells within the inflation radius of the affected block need stamping
        CellRegion sources = affected.expand(kernelRadius).clip(width, geometry.height());
        for (int row = sources.minRow(); row <= sources.maxRow(); row++) {
            for (int column = sources.minColumn(); column <= sources.maxColumn(); column++) {
                if (isLethal(column, row) && isBoundary(column, row)) {
                    stamp(column, row, affected);
                }
            }
        }
    }

    private boolean isLethal(int column, int row) {
        return (obstacles[row * geometry.width() + column] & 0xFF) == Costmap.LETHAL;
    }

    private boolean isBoundary(int column, int row) {
        return column == 0 || row == 0 || column == geometry.width() - 1 || row == geometry.height() - 1
                || !isLethal(column + 1, row) || !isLethal(column - 1, row) || !isLethal(column, row + 1)
                || !isLethal(column, row - 1);
    }

    private void stamp(int column, int row, CellRegion affected) {
        int width = geometry.width();
        for (int k = 0; k < kernelCost.length; k++) {
            int c = column + kernelDx[k];
            int r = row + kernelDy[k];
            if (!affected.contains(c, r)) {
                continue;
            }
            int index = r * width + c;
            int current = inflated[index] & 0xFF;
            int cost = kernelCost[k] & 0xFF;
            if (current == Costmap.NO_INFORMATION) {
                // costmap_2d: unknown cells are overwritten only by impassable inflation
                if (cost >= Costmap.INSCRIBED) {
                    inflated[index] = (byte) cost;
                }
            } else if (cost > current) {
                inflated[index] = (byte) cost;
            }
        }
    }

    private void publish(CellRegion region) {
        if (region.isEmpty()) {
            return;
        }
        combine(region);
        costmap.copyFrom(composite, region);
    }

    private void combine(CellRegion region) {
        int width = geometry.width();
        for (int row = region.minRow(); row <= region.maxRow(); row++) {
            int base = row * width;
            for (int column = region.minColumn(); column <= region.maxColumn(); column++) {
                int index = base + column;
                int cost = inflated[index] & 0xFF;
                if (cost <= Costmap.MAX_GRADED) {
                    cost = Math.max(cost, moving[index] & 0xFF);
                }
                composite[index] = (byte) cost;
            }
        }
    }

    private void clearRegion(byte[] layer, CellRegion region) {
        if (region.isEmpty()) {
            return;
        }
        int width = geometry.width();
        for (int row = region.minRow(); row <= region.maxRow(); row++) {
            Arrays.fill(layer, row * width + region.minColumn(), row * width + region.maxColumn() + 1, (byte) 0);
        }
    }
}
