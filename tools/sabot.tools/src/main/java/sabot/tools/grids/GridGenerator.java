package sabot.tools.grids;

import java.io.IOException;
import java.nio.file.Path;

import sabot.model.geometry.Point2D;
import sabot.model.map.Cell;
import sabot.model.map.GridGeometry;
import sabot.model.map.MapServerFormat;

/**
 * Writes a benchmark grid as a raw costmap PGM for {@code sabot plan --costmap} and prints the start and goal as
 * {@code --start C,R --goal C,R --cells} (image row 0 at the top).
 *
 * <pre>./sabot bench planner --grid random-1000 /tmp/random-1000.pgm
 * java -cp sabot-tools.jar sabot.tools.grids.GridGenerator random-1000 /tmp/random-1000.pgm</pre>
 *
 * The grids are {@link BenchmarkGrids}' (fixed seed), so a plan on the image meets the benchmarks' figures.
 */
public final class GridGenerator {

    private GridGenerator() {
    }

    public static void main(String[] args) throws IOException {
        if (args.length != 2) {
            System.err.println("usage: GridGenerator (random|maze|enclosed)-SIZE OUT.pgm");
            System.exit(2);
        }
        BenchmarkGrids.Scenario scenario = BenchmarkGrids.scenario(args[0]);
        MapServerFormat.saveCostmapImage(scenario.costmap(), Path.of(args[1]));
        GridGeometry g = scenario.costmap().geometry();
        System.out.println("--start " + imageCell(g, scenario.start()) + " --goal " + imageCell(g, scenario.goal())
                + " --cells");
    }

    private static String imageCell(GridGeometry geometry, Point2D point) {
        Cell cell = geometry.cellAt(point).orElseThrow();
        return cell.column() + "," + (geometry.height() - 1 - cell.row());
    }
}
