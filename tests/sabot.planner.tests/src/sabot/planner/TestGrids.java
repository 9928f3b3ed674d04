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
