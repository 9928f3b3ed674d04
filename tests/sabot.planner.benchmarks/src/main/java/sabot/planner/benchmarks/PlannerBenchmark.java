package sabot.planner.benchmarks;

import java.util.List;
import java.util.concurrent.TimeUnit;

import org.openjdk.jmh.annotations.Benchmark;
import org.openjdk.jmh.annotations.BenchmarkMode;
import org.openjdk.jmh.annotations.Fork;
import org.openjdk.jmh.annotations.Measurement;
import org.openjdk.jmh.annotations.Mode;
import org.openjdk.jmh.annotations.OutputTimeUnit;
import org.openjdk.jmh.annotations.Param;
import org.openjdk.jmh.annotations.Scope;
import org.openjdk.jmh.annotations.Setup;
import org.openjdk.jmh.annotations.State;
import org.openjdk.jmh.annotations.Warmup;

import sabot.model.map.Cell;
import sabot.model.map.GridGeometry;
import sabot.planner.CostModel;
import sabot.planner.PlanResult;
import sabot.planner.Planner;
import sabot.planner.Planners;
import sabot.planner.internal.LpnNavigationFunction;
import sabot.planner.internal.PlanningGrid;
import sabot.tools.grids.BenchmarkGrids;

/**
 * Planner figures on the {@link BenchmarkGrids}: the LPN navigation function alone, LPN's full plan (navigation
 * function plus path extraction, what {@code sabot plan} times), and the A* reference. Sample-time mode: JMH reports the median (p0.50) per
 * operation.
 */
@State(Scope.Benchmark)
@BenchmarkMode(Mode.SampleTime)
@OutputTimeUnit(TimeUnit.MILLISECONDS)
@Warmup(iterations = 3, time = 1)
@Measurement(iterations = 5, time = 1)
@Fork(value = 1, jvmArgsAppend = { "-Xms1g", "-Xmx1g" })
public class PlannerBenchmark {

    @Param({ "random-100", "random-1000", "random-2000", "maze-1000", "enclosed-1000" })
    public String grid;

    private BenchmarkGrids.Scenario scenario;
    private Planner lpn;
    private Planner reference;
    private LpnNavigationFunction navigationFunction;
    private int[] goalCells;

    @Setup
    public void setUp() {
        scenario = BenchmarkGrids.scenario(grid);
        lpn = Planners.lpn();
        reference = Planners.reference();
        PlanningGrid planningGrid = new PlanningGrid();
        navigationFunction = new LpnNavigationFunction(CostModel.standard());
        navigationFunction.gridChanged(planningGrid, planningGrid.sync(scenario.costmap()));
        GridGeometry geometry = scenario.costmap().geometry();
        Cell goal = geometry.cellAt(scenario.goal()).orElseThrow();
        goalCells = new int[] { planningGrid.index(goal.column(), goal.row()) };
        boolean expectFound = !grid.startsWith("enclosed");
        if (lpn.plan(scenario.costmap(), scenario.start(), scenario.goal()).isFound() != expectFound) {
            throw new IllegalStateException(grid + ": unexpected reachability");
        }
    }

    /** The navigation function over the whole reachable grid. */
    @Benchmark
    public int lpnNavigationFunction() {
        navigationFunction.compute(goalCells, -1);
        return navigationFunction.finalizedCount();
    }

    /** Navigation function plus gradient-descent path (the figure {@code sabot plan} reports). */
    @Benchmark
    public PlanResult lpnPlan() {
        return lpn.plan(scenario.costmap(), scenario.start(), List.of(scenario.goal()));
    }

    /** The 8-connected A* reference on the same cost model. */
    @Benchmark
    public PlanResult referencePlan() {
        return reference.plan(scenario.costmap(), scenario.start(), List.of(scenario.goal()));
    }
}
