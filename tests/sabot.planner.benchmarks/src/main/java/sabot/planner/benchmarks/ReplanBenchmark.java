package sabot.planner.benchmarks;

import java.util.List;
import java.util.concurrent.TimeUnit;

import org.openjdk.jmh.annotations.Benchmark;
import org.openjdk.jmh.annotations.BenchmarkMode;
import org.openjdk.jmh.annotations.Fork;
import org.openjdk.jmh.annotations.Level;
import org.openjdk.jmh.annotations.Measurement;
import org.openjdk.jmh.annotations.Mode;
import org.openjdk.jmh.annotations.OutputTimeUnit;
import org.openjdk.jmh.annotations.Param;
import org.openjdk.jmh.annotations.Scope;
import org.openjdk.jmh.annotations.Setup;
import org.openjdk.jmh.annotations.State;
import org.openjdk.jmh.annotations.Warmup;

import sabot.model.geometry.Point2D;
import sabot.model.map.CellRegion;
import sabot.model.map.Costmap;
import sabot.planner.CostModel;
import sabot.planner.PlanResult;
import sabot.planner.Planner;
import sabot.planner.Planners;
import sabot.tools.grids.BenchmarkGrids;

/**
 * Re-planning after a local change: a sonar obstacle appears on the path half a metre ahead of the robot. Each
 * operation is the costmap's regional update plus the new plan; before each one (not timed) the obstacle is removed
 * again and the planner plans once on the clear map. {@code lpn} recomputes the navigation function, {@code
 * lpn-incremental} repairs it where the obstacle's shadow reaches.
 */
@State(Scope.Benchmark)
@BenchmarkMode(Mode.SampleTime)
@OutputTimeUnit(TimeUnit.MILLISECONDS)
@Warmup(iterations = 3, time = 1)
@Measurement(iterations = 5, time = 1)
@Fork(value = 1, jvmArgsAppend = { "-Xms1g", "-Xmx1g" })
public class ReplanBenchmark {

    @Param({ "random-1000" })
    public String grid;

    @Param({ "lpn", "lpn-incremental" })
    public String planner;

    private BenchmarkGrids.Scenario scenario;
    private Planner lpn;
    private Point2D obstacle;
    private CellRegion obstacleCell;

    @Setup(Level.Trial)
    public void setUp() {
        scenario = BenchmarkGrids.scenario(grid);
        lpn = Planners.byName(planner, CostModel.standard()).orElseThrow();
        PlanResult.Found found = (PlanResult.Found) lpn.plan(scenario.costmap(), scenario.start(), scenario.goal());
        List<Point2D> waypoints = found.path().waypoints();
        for (Point2D p : waypoints) {
            if (p.distanceTo(scenario.start()) >= 0.5) {
                obstacle = p;
                break;
            }
        }
        var cell = scenario.costmap().geometry().cellAt(obstacle).orElseThrow();
        obstacleCell = CellRegion.of(cell.column(), cell.row());
    }

    /** Clears the obstacle and plans on the clear map (not timed). */
    @Setup(Level.Invocation)
    public void clearObstacle() {
        scenario.layers().setObstacles(obstacleCell, Costmap.FREE);
        lpn.plan(scenario.costmap(), scenario.start(), List.of(scenario.goal()));
    }

    /** Regional costmap update (obstacle layer, inflation around it) plus the re-plan. */
    @Benchmark
    public PlanResult sonarObstacleThenReplan() {
        scenario.layers().setObstacles(obstacleCell, Costmap.LETHAL);
        return lpn.plan(scenario.costmap(), scenario.start(), List.of(scenario.goal()));
    }

    /** The regional costmap update alone (the obstacle appears; the invocation set-up clears it). */
    @Benchmark
    public CellRegion sonarObstacleCostmapUpdate() {
        return scenario.layers().setObstacles(obstacleCell, Costmap.LETHAL);
    }
}
