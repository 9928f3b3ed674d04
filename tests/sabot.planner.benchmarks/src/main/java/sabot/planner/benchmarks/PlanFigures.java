package sabot.planner.benchmarks;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;

import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.map.GridGeometry;
import sabot.planner.PlanResult;
import sabot.planner.Planner;
import sabot.planner.Planners;
import sabot.planner.costmap.CostmapLayers;
import sabot.planner.costmap.InflationParameters;
import sabot.planner.costmap.MovingObstacle;
import sabot.planner.costmap.MovingObstacleModel;
import sabot.tools.grids.BenchmarkGrids;
import sabot.tools.render.PlanImage;

/**
 * Renders the pictures of docs/PLANNER.md:
 *
 * <pre>java -cp sabot-planner-bench.jar sabot.planner.benchmarks.PlanFigures docs/images</pre>
 */
public final class PlanFigures {

    private PlanFigures() {
    }

    public static void main(String[] args) throws IOException {
        Path folder = Path.of(args.length > 0 ? args[0] : "docs/images");
        Files.createDirectories(folder);
        render(BenchmarkGrids.scenario("random-100"), Planners.lpn(), 6, folder.resolve("planner-random-100-lpn.png"));
        render(BenchmarkGrids.scenario("random-100"), Planners.reference(), 6,
                folder.resolve("planner-random-100-reference.png"));
        render(BenchmarkGrids.scenario("maze-1000"), Planners.lpn(), 1, folder.resolve("planner-maze-1000-lpn.png"));
        movingObstacle(folder);
    }

    private static void render(BenchmarkGrids.Scenario scenario, Planner planner, int scale, Path file)
            throws IOException {
        PlanResult result = planner.plan(scenario.costmap(), scenario.start(), scenario.goal());
        PlanImage image = PlanImage.of(scenario.costmap()).scale(scale);
        if (result instanceof PlanResult.Found found) {
            image.withField(found.field()).withPath(found.path().waypoints());
        }
        image.writePng(file);
        System.out.println(file + ": " + describe(result));
    }

    /** The scene of MovingObstacleTest: a person standing, then walking down across the robot's way at 1 m/s. */
    private static void movingObstacle(Path folder) throws IOException {
        GridGeometry hall = new GridGeometry(200, 120, 0.05, Pose2D.ORIGIN);
        Point2D start = new Point2D(0.5, 3.0);
        Point2D goal = new Point2D(9.5, 3.0);
        Point2D person = new Point2D(5.0, 3.3);
        Planner planner = Planners.lpn();
        for (double vy : new double[] { 0, -1.0 }) {
            CostmapLayers layers = CostmapLayers.free(hall, InflationParameters.forRobot(0.15),
                    MovingObstacleModel.defaults());
            layers.setMovingObstacles(List.of(new MovingObstacle(person, 0, vy, 0.25)), 0.5, 0);
            PlanResult result = planner.plan(layers.costmap(), start, goal);
            Path file = folder.resolve(vy == 0 ? "planner-person-standing.png" : "planner-person-walking.png");
            PlanImage image = PlanImage.of(layers.costmap()).scale(4);
            if (result instanceof PlanResult.Found found) {
                image.withPath(found.path().waypoints());
            }
            image.writePng(file);
            System.out.println(file + ": " + describe(result));
        }
    }

    private static String describe(PlanResult result) {
        return switch (result) {
            case PlanResult.Found f -> String.format(java.util.Locale.ROOT, "path %.2f m, cost %.0f, %d waypoints",
                    f.path().length(), f.path().cost(), f.path().waypoints().size());
            case PlanResult.Unreachable u -> "unreachable: " + u.reason() + " (" + u.detail() + ")";
        };
    }
}
