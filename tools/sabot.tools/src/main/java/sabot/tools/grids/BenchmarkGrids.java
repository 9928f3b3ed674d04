package sabot.tools.grids;

import java.util.ArrayDeque;
import java.util.Random;

import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.map.Cell;
import sabot.model.map.Costmap;
import sabot.model.map.GridGeometry;
import sabot.model.map.OccupancyGrid;
import sabot.planner.costmap.CostmapLayers;
import sabot.planner.costmap.InflationParameters;
import sabot.planner.costmap.MovingObstacleModel;
import sabot.planner.costmap.UnknownCellPolicy;

/**
 * The fixed-seed grids the planner figures are measured on (the JMH benchmarks, {@code ./sabot bench navfn}, the
 * pictures of docs/PLANNER.md), and that {@link GridGenerator} writes as images for {@code ./sabot plan}. Every grid has 0.05 m cells; the random grids are
 * inflated for a robot of inscribed radius 0.10 m (2 cells) with cost spreading to 0.30 m (6 cells), decay 10 per
 * metre.
 * <ul>
 * <li>{@code random-N}: N x N cells, about 20 % of them in random rectangles (2 to 2 + N/25 cells a side); start near
 * the lower-left corner, goal near the upper-right one, in the same free region;</li>
 * <li>{@code maze-N}: a perfect maze (randomised depth-first search) of 8-cell corridors between 2-cell walls, not
 * inflated: lethal walls, free corridors, so that it measures the propagation along long winding corridors (inflated,
 * every corridor cell would have a graded cost, and navfn's 100-unit threshold bands would re-update cells hundreds of
 * times: a test of navfn's thresholds, not of the propagation order); start and goal in opposite corners;</li>
 * <li>{@code enclosed-N}: {@code random-N} with the goal at the centre inside a closed lethal ring.</li>
 * </ul>
 */
public final class BenchmarkGrids {

    /** Seed of every published figure. */
    public static final long SEED = 20001;
    static final double RESOLUTION = 0.05;
    static final InflationParameters INFLATION = new InflationParameters(0.10, 0.30, 10.0, 100,
            UnknownCellPolicy.KEEP_UNKNOWN);
    /** The maze's: none, occupied cells lethal and free cells free. */
    static final InflationParameters NO_INFLATION = new InflationParameters(0, 0, 10.0, 100,
            UnknownCellPolicy.KEEP_UNKNOWN);

    /** A grid to plan on, with the layers that produced it (for local changes) and start and goal in metres. */
    public record Scenario(String name, CostmapLayers layers, Point2D start, Point2D goal) {
        public Costmap costmap() {
            return layers.costmap();
        }
    }

    private BenchmarkGrids() {
    }

    /** @param name {@code random-N}, {@code maze-N} or {@code enclosed-N} */
    public static Scenario scenario(String name) {
        int dash = name.lastIndexOf('-');
        if (dash < 0) {
            throw new IllegalArgumentException("scenario '" + name + "' is not KIND-SIZE, e.g. random-1000");
        }
        String kind = name.substring(0, dash);
        int size = Integer.parseInt(name.substring(dash + 1));
        return switch (kind) {
            case "random" -> random(name, size, SEED, false);
            case "enclosed" -> random(name, size, SEED, true);
            case "maze" -> maze(name, size, SEED);
            default -> throw new IllegalArgumentException("unknown grid kind '" + kind + "' (random, maze, enclosed)");
        };
    }

    static Scenario random(String name, int size, long seed, boolean enclosedGoal) {
        Random random = new Random(seed);
        OccupancyGrid grid = freeGrid(size);
        long target = (long) (0.2 * size * size);
        long filled = 0;
        int maxSide = 2 + size / 25;
        while (filled < target) {
            int w = 2 + random.nextInt(maxSide - 1);
            int h = 2 + random.nextInt(maxSide - 1);
            int c0 = random.nextInt(size);
            int r0 = random.nextInt(size);
            for (int r = r0; r < Math.min(size, r0 + h); r++) {
                for (int c = c0; c < Math.min(size, c0 + w); c++) {
                    if (grid.get(c, r) != OccupancyGrid.OCCUPIED) {
                        grid.set(c, r, OccupancyGrid.OCCUPIED);
                        filled++;
                    }
                }
            }
        }
        Cell goalCell = null;
        if (enclosedGoal) {
            int centre = size / 2;
            int ring = 7;
            for (int r = centre - ring; r <= centre + ring; r++) {
                for (int c = centre - ring; c <= centre + ring; c++) {
                    boolean onRing = Math.max(Math.abs(r - centre), Math.abs(c - centre)) == ring;
                    grid.set(c, r, onRing ? OccupancyGrid.OCCUPIED : OccupancyGrid.FREE);
                }
            }
            goalCell = new Cell(centre, centre);
        }
        CostmapLayers layers = CostmapLayers.fromOccupancy(grid, INFLATION, MovingObstacleModel.defaults());
        Costmap costmap = layers.costmap();
        Cell start = nearestFree(costmap, 2, 2);
        if (goalCell == null) {
            goalCell = farthestCornerInRegion(costmap, start, size - 3, size - 3);
        }
        return new Scenario(name, layers, centre(costmap, start), centre(costmap, goalCell));
    }

    static Scenario maze(String name, int size, long seed) {
        int corridor = 8;
        int wall = 2;
        int pitch = corridor + wall;
        int nodes = (size - wall) / pitch;
        OccupancyGrid grid = OccupancyGrid.unknown(size, size, RESOLUTION, Pose2D.ORIGIN);
        for (int r = 0; r < size; r++) {
            for (int c = 0; c < size; c++) {
                grid.set(c, r, OccupancyGrid.OCCUPIED);
            }
        }
        boolean[] visited = new boolean[nodes * nodes];
        Random random = new Random(seed);
        ArrayDeque<Integer> stack = new ArrayDeque<>();
        stack.push(0);
        visited[0] = true;
        carve(grid, 0, 0, 0, 0, pitch, wall, corridor);
        int[][] steps = { { 1, 0 }, { -1, 0 }, { 0, 1 }, { 0, -1 } };
        while (!stack.isEmpty()) {
            int node = stack.peek();
            int nx = node % nodes;
            int ny = node / nodes;
            int[] options = new int[4];
            int count = 0;
            for (int k = 0; k < 4; k++) {
                int x = nx + steps[k][0];
                int y = ny + steps[k][1];
                if (x >= 0 && y >= 0 && x < nodes && y < nodes && !visited[y * nodes + x]) {
                    options[count++] = k;
                }
            }
            if (count == 0) {
                stack.pop();
                continue;
            }
            int k = options[random.nextInt(count)];
            int x = nx + steps[k][0];
            int y = ny + steps[k][1];
            visited[y * nodes + x] = true;
            carve(grid, nx, ny, x, y, pitch, wall, corridor);
            stack.push(y * nodes + x);
        }
        CostmapLayers layers = CostmapLayers.fromOccupancy(grid, NO_INFLATION, MovingObstacleModel.defaults());
        Costmap costmap = layers.costmap();
        int half = wall + corridor / 2;
        Cell start = new Cell(half, half);
        Cell goal = new Cell((nodes - 1) * pitch + half, (nodes - 1) * pitch + half);
        return new Scenario(name, layers, centre(costmap, start), centre(costmap, goal));
    }

    /** Frees the corridor block of node (x0, y0), of node (x1, y1) and the wall between them. */
    private static void carve(OccupancyGrid grid, int x0, int y0, int x1, int y1, int pitch, int wall, int corridor) {
        int c0 = Math.min(x0, x1) * pitch + wall;
        int r0 = Math.min(y0, y1) * pitch + wall;
        int c1 = Math.max(x0, x1) * pitch + wall + corridor - 1;
        int r1 = Math.max(y0, y1) * pitch + wall + corridor - 1;
        for (int r = r0; r <= r1; r++) {
            for (int c = c0; c <= c1; c++) {
                grid.set(c, r, OccupancyGrid.FREE);
            }
        }
    }

    private static OccupancyGrid freeGrid(int size) {
        OccupancyGrid grid = OccupancyGrid.of(new GridGeometry(size, size, RESOLUTION, Pose2D.ORIGIN),
                new byte[size * size]);
        return grid;
    }

    private static Point2D centre(Costmap costmap, Cell cell) {
        return costmap.geometry().cellCentre(cell.column(), cell.row());
    }

    private static Cell nearestFree(Costmap costmap, int column, int row) {
        for (int d = 0; d < Math.max(costmap.width(), costmap.height()); d++) {
            for (int dr = -d; dr <= d; dr++) {
                for (int dc = -d; dc <= d; dc++) {
                    int c = column + dc;
                    int r = row + dr;
                    if (costmap.geometry().contains(c, r) && costmap.cost(c, r) == Costmap.FREE) {
                        return new Cell(c, r);
                    }
                }
            }
        }
        throw new IllegalStateException("no free cell in the grid");
    }

    /** The cell of the start's 4-connected free region closest to (column, row). */
    private static Cell farthestCornerInRegion(Costmap costmap, Cell start, int column, int row) {
        int width = costmap.width();
        boolean[] seen = new boolean[width * costmap.height()];
        int[] queue = new int[seen.length];
        int head = 0;
        int tail = 0;
        queue[tail++] = start.row() * width + start.column();
        seen[queue[0]] = true;
        Cell best = start;
        double bestDistance = Double.MAX_VALUE;
        int[][] steps = { { 1, 0 }, { -1, 0 }, { 0, 1 }, { 0, -1 } };
        while (head < tail) {
            int index = queue[head++];
            int c = index % width;
            int r = index / width;
            double distance = Math.hypot(c - column, r - row);
            if (costmap.cost(c, r) == Costmap.FREE && distance < bestDistance) {
                bestDistance = distance;
                best = new Cell(c, r);
            }
            for (int[] s : steps) {
                int nc = c + s[0];
                int nr = r + s[1];
                if (costmap.geometry().contains(nc, nr) && !seen[nr * width + nc]
                        && costmap.cost(nc, nr) <= Costmap.MAX_GRADED) {
                    seen[nr * width + nc] = true;
                    queue[tail++] = nr * width + nc;
                }
            }
        }
        return best;
    }
}
