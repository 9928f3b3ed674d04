package sabot.planner;

import java.util.Random;

import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.map.Costmap;
import sabot.model.map.GridGeometry;

/** Small deterministic costmaps for tests: 1 m cells, origin at (0, 0). */
public final class TestGrids {

    private TestGrids() {
    }

    public static GridGeometry geometry(int width, int height) {
        return new GridGeometry(width, height, 1.0, Pose2D.ORIGIN);
    }

    public static Costmap free(int width, int height) {
        return Costmap.filled(geometry(width, height), Costmap.FREE);
    }

    /**
     * A random costmap: lethal rectangles covering about {@code fill} of the area, a ring of inscribed cells and a
     * band of graded cost around each, so that every cost class appears.
     */
    public static Costmap random(long seed, int width, int height, double fill) {
        Random random = new Random(seed);
        Costmap costmap = free(width, height);
        int target = (int) (fill * width * height);
        int covered = 0;
        while (covered < target) {
            int w = 1 + random.nextInt(Math.max(1, width / 5));
            int h = 1 + random.nextInt(Math.max(1, height / 5));
            int c0 = random.nextInt(width);
            int r0 = random.nextInt(height);
            for (int r = r0; r < Math.min(height, r0 + h); r++) {
                for (int c = c0; c < Math.min(width, c0 + w); c++) {
                    if (costmap.cost(c, r) != Costmap.LETHAL) {
                        costmap.set(c, r, Costmap.LETHAL);
                        covered++;
                    }
                }
            }
        }
        byte[] costs = costmap.toArray();
        for (int r = 0; r < height; r++) {
            for (int c = 0; c < width; c++) {
                if ((costs[r * width + c] & 0xFF) == Costmap.LETHAL) {
                    continue;
                }
                int distance = distanceToLethal(costmap, c, r, 3);
                if (distance == 1 && random.nextInt(4) == 0) {
                    costs[r * width + c] = (byte) Costmap.INSCRIBED;
                } else if (distance <= 3) {
                    costs[r * width + c] = (byte) (200 / distance);
                } else if (random.nextInt(10) == 0) {
                    costs[r * width + c] = (byte) random.nextInt(60);
                }
            }
        }
        return Costmap.of(costmap.geometry(), costs);
    }

    private static int distanceToLethal(Costmap costmap, int c, int r, int limit) {
        for (int d = 1; d <= limit; d++) {
            for (int dr = -d; dr <= d; dr++) {
                for (int dc = -d; dc <= d; dc++) {
                    if (Math.max(Math.abs(dr), Math.abs(dc)) == d && costmap.geometry().contains(c + dc, r + dr)
                            && costmap.cost(c + dc, r + dr) == Costmap.LETHAL) {
                        return d;
                    }
                }
            }
        }
        return Integer.MAX_VALUE;
    }

    /**
     * A maze (randomised depth-first search over {@code nodes} x {@code nodes} rooms) of 3-cell corridors between
     * 1-cell lethal walls, with a graded band (cost 120 to 127) on the corridor cells beside a wall: paths many times
     * the straight line, as in the benchmark's maze, on a grid a test plans on quickly.
     *
     * @param loops true to open about a tenth of the remaining walls between rooms, so that there are dearer routes
     *              a focused propagation could wrongly settle for; false for a perfect maze (one route)
     */
    public static Costmap maze(long seed, int nodes, boolean loops) {
        Random random = new Random(seed);
        int corridor = 3;
        int pitch = corridor + 1;
        int size = nodes * pitch + 1;
        Costmap costmap = Costmap.filled(geometry(size, size), Costmap.LETHAL);
        boolean[] visited = new boolean[nodes * nodes];
        int[] stack = new int[nodes * nodes];
        int depth = 0;
        stack[depth++] = 0;
        visited[0] = true;
        carve(costmap, 0, 0, 0, 0, corridor, pitch);
        int[][] moves = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
        while (depth > 0) {
            int node = stack[depth - 1];
            int x = node % nodes;
            int y = node / nodes;
            int[] open = new int[4];
            int options = 0;
            for (int m = 0; m < 4; m++) {
                int nx = x + moves[m][0];
                int ny = y + moves[m][1];
                if (nx >= 0 && ny >= 0 && nx < nodes && ny < nodes && !visited[ny * nodes + nx]) {
                    open[options++] = m;
                }
            }
            if (options == 0) {
                depth--;
                continue;
            }
            int[] move = moves[open[random.nextInt(options)]];
            int next = (y + move[1]) * nodes + x + move[0];
            visited[next] = true;
            carve(costmap, x, y, x + move[0], y + move[1], corridor, pitch);
            stack[depth++] = next;
        }
        // a few walls opened at random: loops, so that a route can be missed in favour of a dearer one
        for (int y = 0; loops && y < nodes; y++) {
            for (int x = 0; x < nodes; x++) {
                if (x + 1 < nodes && random.nextInt(10) == 0) {
                    carve(costmap, x, y, x + 1, y, corridor, pitch);
                }
                if (y + 1 < nodes && random.nextInt(10) == 0) {
                    carve(costmap, x, y, x, y + 1, corridor, pitch);
                }
            }
        }
        // a graded band along the walls, as inflation gives: the corridor's outer cells cost more than its middle
        Costmap graded = Costmap.filled(costmap.geometry(), Costmap.FREE);
        for (int r = 0; r < size; r++) {
            for (int c = 0; c < size; c++) {
                int cost = costmap.cost(c, r);
                if (cost == Costmap.FREE && nextToWall(costmap, c, r)) {
                    cost = 120 + random.nextInt(8);
                }
                graded.set(c, r, cost);
            }
        }
        return graded;
    }

    private static boolean nextToWall(Costmap costmap, int c, int r) {
        for (int dr = -1; dr <= 1; dr++) {
            for (int dc = -1; dc <= 1; dc++) {
                int nc = c + dc;
                int nr = r + dr;
                if (nc >= 0 && nr >= 0 && nc < costmap.width() && nr < costmap.height()
                        && costmap.cost(nc, nr) == Costmap.LETHAL) {
                    return true;
                }
            }
        }
        return false;
    }

    /** Frees the rooms of two neighbouring maze nodes and the wall between them. */
    private static void carve(Costmap costmap, int x0, int y0, int x1, int y1, int corridor, int pitch) {
        int c0 = 1 + Math.min(x0, x1) * pitch;
        int r0 = 1 + Math.min(y0, y1) * pitch;
        int c1 = 1 + Math.max(x0, x1) * pitch + corridor;
        int r1 = 1 + Math.max(y0, y1) * pitch + corridor;
        for (int r = r0; r < r1; r++) {
            for (int c = c0; c < c1; c++) {
                costmap.set(c, r, Costmap.FREE);
            }
        }
    }

    /** @return the centre of a random passable cell */
    public static Point2D randomFreePoint(Random random, Costmap costmap) {
        while (true) {
            int c = random.nextInt(costmap.width());
            int r = random.nextInt(costmap.height());
            if (costmap.cost(c, r) <= Costmap.MAX_GRADED) {
                return new Point2D(c + 0.2 + 0.6 * random.nextDouble(), r + 0.2 + 0.6 * random.nextDouble());
            }
        }
    }
}
