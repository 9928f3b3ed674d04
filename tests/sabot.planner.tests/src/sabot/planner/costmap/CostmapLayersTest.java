package sabot.planner.costmap;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.Random;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.EnumSource;

import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.map.CellRegion;
import sabot.model.map.Costmap;
import sabot.model.map.OccupancyGrid;

/** Inflation by the robot's radius, unknown-cell policy and cheap regional updates. */
class CostmapLayersTest {

    /** 0.1 m cells, inscribed 0.25 m, inflation to 0.6 m, decay 5 per metre. */
    private static final InflationParameters ROBOT = new InflationParameters(0.25, 0.6, 5.0, 100,
            UnknownCellPolicy.KEEP_UNKNOWN);

    private static OccupancyGrid freeGrid(int width, int height) {
        OccupancyGrid grid = OccupancyGrid.unknown(width, height, 0.1, Pose2D.ORIGIN);
        for (int r = 0; r < height; r++) {
            for (int c = 0; c < width; c++) {
                grid.set(c, r, OccupancyGrid.FREE);
            }
        }
        return grid;
    }

    @Test
    void obstacleIsLethalInscribedCellsImpassableAndCostDecaysBeyond() {
        OccupancyGrid grid = freeGrid(40, 40);
        grid.set(20, 20, OccupancyGrid.OCCUPIED);
        Costmap costmap = CostmapLayers.fromOccupancy(grid, ROBOT, MovingObstacleModel.defaults()).costmap();
        assertEquals(Costmap.LETHAL, costmap.cost(20, 20));
        assertEquals(Costmap.INSCRIBED, costmap.cost(22, 20), "0.2 m away, within the inscribed radius");
        assertEquals(Costmap.INSCRIBED, costmap.cost(21, 21), "0.14 m away");
        int at3 = costmap.cost(23, 20);
        int at4 = costmap.cost(24, 20);
        int at5 = costmap.cost(25, 20);
        assertEquals((int) (252 * Math.exp(-5.0 * (0.3 - 0.25))), at3, "costmap_2d decay at 0.3 m");
        assertTrue(at3 > at4 && at4 > at5 && at5 > 0, at3 + " > " + at4 + " > " + at5);
        assertEquals(Costmap.FREE, costmap.cost(27, 20), "0.7 m is beyond the inflation radius");
    }

    @ParameterizedTest
    @EnumSource(UnknownCellPolicy.class)
    void unknownCellsFollowThePolicy(UnknownCellPolicy policy) {
        OccupancyGrid grid = freeGrid(30, 30);
        grid.set(15, 15, OccupancyGrid.UNKNOWN);
        Costmap costmap = CostmapLayers.fromOccupancy(grid, ROBOT.withUnknownCells(policy),
                MovingObstacleModel.defaults()).costmap();
        int expected = switch (policy) {
            case FREE -> Costmap.FREE;
            case LETHAL -> Costmap.LETHAL;
            case KEEP_UNKNOWN -> Costmap.NO_INFORMATION;
        };
        assertEquals(expected, costmap.cost(15, 15));
        assertEquals(policy == UnknownCellPolicy.LETHAL ? Costmap.INSCRIBED : Costmap.FREE, costmap.cost(17, 15));
    }

    @Test
    void newObstacleUpdatesOnlyItsNeighbourhoodAndMatchesAFullRebuild() {
        Random random = new Random(11);
        OccupancyGrid grid = freeGrid(120, 90);
        for (int i = 0; i < 300; i++) {
            grid.set(random.nextInt(120), random.nextInt(90), random.nextInt(10) == 0 ? -1 : 100);
        }
        CostmapLayers layers = CostmapLayers.fromOccupancy(grid, ROBOT, MovingObstacleModel.defaults());
        long version = layers.costmap().version();

        assertTrue(layers.markObstacle(new Point2D(6.05, 4.05)));
        CellRegion changed = layers.costmap().changedSince(version);
        assertEquals(new CellRegion(54, 34, 66, 46), changed, "a sonar hit recomputes the inflation radius around it");
        assertFalse(layers.markObstacle(new Point2D(-1, 0)), "outside the map");

        grid.set(60, 40, OccupancyGrid.OCCUPIED);
        Costmap rebuilt = CostmapLayers.fromOccupancy(grid, ROBOT, MovingObstacleModel.defaults()).costmap();
        assertArrayEquals(rebuilt.toArray(), layers.costmap().toArray());

        layers.setObstacles(new CellRegion(60, 40, 60, 40), Costmap.FREE);
        grid.set(60, 40, OccupancyGrid.FREE);
        assertArrayEquals(CostmapLayers.fromOccupancy(grid, ROBOT, MovingObstacleModel.defaults()).costmap().toArray(),
                layers.costmap().toArray(), "clearing restores the costs");
    }

    @Test
    void badInflationParametersAreRejected() {
        assertThrows(IllegalArgumentException.class, () -> InflationParameters.forRobot(-0.1));
        assertThrows(IllegalArgumentException.class, () -> InflationParameters.forRobot(0.2).withDecay(0.1, 10));
        assertThrows(IllegalArgumentException.class, () -> InflationParameters.forRobot(0.2).withDecay(0.5, 0));
    }
}
