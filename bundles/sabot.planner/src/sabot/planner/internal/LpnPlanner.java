package sabot.planner.internal;

import java.util.ArrayList;
import java.util.List;
import java.util.Optional;

import sabot.model.geometry.Point2D;
import sabot.model.map.CellRegion;
import sabot.model.map.Costmap;
import sabot.model.map.GridGeometry;
import sabot.planner.CostModel;
import sabot.planner.PlanResult;
import sabot.planner.PlannedPath;
import sabot.planner.Planner;

/** The LPN planner: navigation function ({@link LpnNavigationFunction}) then gradient descent ({@link GradientDescent}). */
public final class LpnPlanner implements Planner {

    private final CostModel costModel;
    private final boolean wholeGrid;
    private final boolean incremental;
    private final float[] density;
    private final PlanningGrid grid = new PlanningGrid();
    private final LpnNavigationFunction navigationFunction;
    private boolean focused;

    /**
     * @param wholeGrid true to compute N over the whole reachable grid (a navigation function valid from anywhere);
     *                  false to stop once the start's value and its neighbourhood are final (cheaper re-planning)
     */
    public LpnPlanner(CostModel costModel, boolean wholeGrid) {
        this(costModel, wholeGrid, false);
    }

    /** The focused planner ({@link LpnNavigationFunction#computeFocused}), {@code lpn-focused}. */
    public static LpnPlanner focused(CostModel costModel) {
        return focused(costModel, new LpnNavigationFunction(costModel));
    }

    /** The focused planner with a navigation function made for it (same cost model). */
    public static LpnPlanner focused(CostModel costModel, LpnNavigationFunction navigationFunction) {
        LpnPlanner planner = new LpnPlanner(costModel, false, false, navigationFunction);
        planner.focused = true;
        return planner;
    }

    /**
     * @param incremental true to repair the previous navigation function after costs rose locally (same goals)
     *                    instead of recomputing it; needs {@code wholeGrid}
     */
    public LpnPlanner(CostModel costModel, boolean wholeGrid, boolean incremental) {
        this(costModel, wholeGrid, incremental, 1);
    }

    /** @param threads 1 or 2, both on the calling thread (see {@link LpnNavigationFunction#LpnNavigationFunction(CostModel, int)}) */
    public LpnPlanner(CostModel costModel, boolean wholeGrid, boolean incremental, int threads) {
        this(costModel, wholeGrid, incremental, new LpnNavigationFunction(costModel, threads));
    }

    /** With a navigation function made for it (same cost model). */
    public LpnPlanner(CostModel costModel, boolean wholeGrid, boolean incremental,
            LpnNavigationFunction navigationFunction) {
        if (incremental && !wholeGrid) {
            throw new IllegalArgumentException("incremental re-planning repairs a navigation function over the whole grid");
        }
        this.incremental = incremental;
        this.costModel = costModel;
        this.wholeGrid = wholeGrid;
        this.density = costModel.densityTable();
        this.navigationFunction = navigationFunction;
    }

    @Override
    public void close() {
        navigationFunction.close();
    }

    @Override
    public String name() {
        return incremental ? "lpn-incremental" : wholeGrid ? "lpn" : focused ? "lpn-focused" : "lpn-bounded";
    }

    @Override
    public PlanResult plan(Costmap costmap, Point2D start, List<Point2D> goals) {
        Optional<PlanResult.Unreachable> problem = PlanRequest.problem(costmap, costModel, start, goals);
        if (problem.isPresent()) {
            return problem.get();
        }
        CellRegion changed = grid.sync(costmap);
        PlanRequest request = PlanRequest.resolve(grid, start, goals);
        if (!(incremental && navigationFunction.repair(grid, changed, request.goalCells()))) {
            navigationFunction.gridChanged(grid, changed);
            if (focused) {
                navigationFunction.computeFocused(request.goalCells(), request.startCell());
            } else {
                navigationFunction.compute(request.goalCells(), wholeGrid ? -1 : request.startCell());
            }
        }
        if (!navigationFunction.isReached(request.startCell())) {
            return PlanRequest.enclosed(navigationFunction.finalizedCount());
        }
        double[] points = GradientDescent.descend(grid, navigationFunction.potential(), density,
                costModel.minDensity(), request.startX(), request.startY(), request.goalPoints());
        List<Point2D> waypoints = toMap(grid.geometry(), points, start, goals, request.goalPoints());
        PlannedPath path = new PlannedPath(waypoints, CostModel.length(waypoints), pathCost(waypoints));
        return new PlanResult.Found(path,
                new GridField(grid.geometry(), navigationFunction.potential(), navigationFunction.finalizedCount()));
    }

    /**
     * {@link CostModel#pathCost} of the waypoints on the costmap just synced, over the grid's copy of its cells: the
     * same integral, cell for cell (the copy holds the costmap's costs, and its padding ring is lethal like the
     * outside of the map), without the costmap's checked lookup (the final {@code PaddedDensity}'s lookup is inlined
     * into the shared traversal).
     */
    private double pathCost(List<Point2D> waypoints) {
        return GridTraversal.integrate(grid.geometry(), waypoints, new GridTraversal.PaddedDensity(grid, density));
    }

    /**
     * @return the waypoints in map coordinates; the first is {@code start} itself and the last the goal point itself
     *         (not a round trip through grid coordinates), so that paths end exactly where they were asked to
     */
    static List<Point2D> toMap(GridGeometry geometry, double[] gridPoints, Point2D start, List<Point2D> goals,
            double[] goalGridPoints) {
        int last = gridPoints.length - 2;
        List<Point2D> waypoints = new ArrayList<>(gridPoints.length / 2);
        waypoints.add(start);
        for (int i = 2; i < last; i += 2) {
            waypoints.add(geometry.toMap(gridPoints[i], gridPoints[i + 1]));
        }
        Point2D end = geometry.toMap(gridPoints[last], gridPoints[last + 1]);
        for (int g = 0; g < goals.size(); g++) {
            if (goalGridPoints[2 * g] == gridPoints[last] && goalGridPoints[2 * g + 1] == gridPoints[last + 1]) {
                end = goals.get(g);
            }
        }
        waypoints.add(end);
        return waypoints;
    }
}
