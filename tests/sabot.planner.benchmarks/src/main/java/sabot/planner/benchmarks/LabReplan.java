package sabot.planner.benchmarks;

import java.io.IOException;
import java.nio.file.Path;
import java.util.Arrays;
import java.util.List;
import java.util.Locale;

import sabot.model.geometry.Point2D;
import sabot.model.map.CellRegion;
import sabot.model.map.Costmap;
import sabot.model.map.MapServerFormat;
import sabot.model.map.OccupancyGrid;
import sabot.planner.CostModel;
import sabot.planner.PlanResult;
import sabot.planner.Planner;
import sabot.planner.costmap.CostmapLayers;
import sabot.planner.costmap.InflationParameters;
import sabot.planner.costmap.MovingObstacleModel;
import sabot.planner.internal.LpnNavigationFunction;
import sabot.planner.internal.LpnPlanner;

/**
 * Re-planning after a sonar obstacle on the robot's own map, as the onboard planner task sets it up (robot radius
 * 0.25 m, inflation 0.55 m): plan from START to GOAL, then a lethal cell appears on the path 0.5 m ahead of the robot;
 * timed: the costmap's regional update plus the new plan (the obstacle is cleared and the clear map planned again
 * between repeats, untimed). Prints per planner the median and least time and the cells touched: costmap cells
 * updated, cells the re-plan expanded (the work: a repair's refilled cells, every attempt of a focused computation),
 * cells a repair withdrew, cells with a value afterwards.
 *
 * <pre>java -cp sabot-planner-bench.jar sabot.planner.benchmarks.LabReplan onboard-bridge/maps/lab.yaml 10.5,4.5 1.5,4.0</pre>
 */
public final class LabReplan {

    private LabReplan() {
    }

    public static void main(String[] args) throws IOException {
        OccupancyGrid map = MapServerFormat.load(Path.of(args[0])).grid();
        Point2D start = point(args[1]);
        Point2D goal = point(args[2]);
        int repeats = 301;
        for (String name : List.of("lpn", "lpn-incremental", "lpn-focused", "lpn-bounded")) {
            CostmapLayers layers = CostmapLayers.fromOccupancy(map,
                    InflationParameters.forRobot(0.25).withDecay(0.55, InflationParameters.DEFAULT_COST_SCALING_FACTOR),
                    MovingObstacleModel.defaults());
            LpnNavigationFunction navigationFunction = new LpnNavigationFunction(CostModel.standard());
            try (Planner planner = lpnPlanner(name, navigationFunction)) {
                PlanResult.Found clear = (PlanResult.Found) planner.plan(layers.costmap(), start, goal);
                Point2D obstacle = clear.path().waypoints().stream().filter(p -> p.distanceTo(start) >= 0.5)
                        .findFirst().orElseThrow();
                var cell = layers.costmap().geometry().cellAt(obstacle).orElseThrow();
                CellRegion obstacleCell = CellRegion.of(cell.column(), cell.row());
                double[] times = new double[repeats];
                CellRegion changed = null;
                PlanResult after = null;
                for (int i = 0; i < repeats; i++) {
                    layers.setObstacles(obstacleCell, Costmap.FREE);
                    planner.plan(layers.costmap(), start, goal);
                    long begin = System.nanoTime();
                    changed = layers.setObstacles(obstacleCell, Costmap.LETHAL);
                    after = planner.plan(layers.costmap(), start, goal);
                    times[i] = (System.nanoTime() - begin) / 1e6;
                }
                Arrays.sort(times);
                PlanResult.Found found = (PlanResult.Found) after;
                System.out.printf(Locale.ROOT, "%s: map %d x %d, obstacle at (%.2f, %.2f): median %.3f ms, least %.3f ms;"
                        + " costmap cells updated %d (%d x %d); cells expanded by the re-plan %d, withdrawn %d;"
                        + " cells with a value after the re-plan %d (clear map %d); path cost %.1f -> %.1f%n", name,
                        map.geometry().width(), map.geometry().height(), obstacle.x(), obstacle.y(),
                        times[repeats / 2], times[0], changed.cellCount(),
                        changed.maxColumn() - changed.minColumn() + 1, changed.maxRow() - changed.minRow() + 1,
                        navigationFunction.expandedCount(), navigationFunction.withdrawnCount(),
                        found.field().reachedCells(), clear.field().reachedCells(), clear.path().cost(),
                        found.path().cost());
            }
        }
    }

    /** The LPN planner of that name on the given navigation function, whose counts are read after the re-plan. */
    private static Planner lpnPlanner(String name, LpnNavigationFunction navigationFunction) {
        CostModel costModel = CostModel.standard();
        return switch (name) {
            case "lpn" -> new LpnPlanner(costModel, true, false, navigationFunction);
            case "lpn-incremental" -> new LpnPlanner(costModel, true, true, navigationFunction);
            case "lpn-bounded" -> new LpnPlanner(costModel, false, false, navigationFunction);
            case "lpn-focused" -> LpnPlanner.focused(costModel, navigationFunction);
            default -> throw new IllegalArgumentException("not an LPN planner: " + name);
        };
    }

    private static Point2D point(String text) {
        String[] xy = text.split(",");
        return new Point2D(Double.parseDouble(xy[0]), Double.parseDouble(xy[1]));
    }
}
