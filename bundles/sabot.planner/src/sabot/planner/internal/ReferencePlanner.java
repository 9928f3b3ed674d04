package sabot.planner.internal;

import java.util.List;
import java.util.Optional;

import sabot.model.geometry.Point2D;
import sabot.model.map.Costmap;
import sabot.planner.CostModel;
import sabot.planner.PlanResult;
import sabot.planner.PlannedPath;
import sabot.planner.Planner;

/**
 * The reference planner: {@link ReferenceSearch} (A* or Dijkstra) on the 8-connected grid; the path runs from the
 * start point through the centres of the cells in between to the goal point.
 */
public final class ReferencePlanner implements Planner {

    private final CostModel costModel;
    private final boolean aStar;
    private final PlanningGrid grid = new PlanningGrid();
    private final ReferenceSearch search;

    /** @param aStar true for A*, false for Dijkstra (which settles every cell cheaper than the start) */
    public ReferencePlanner(CostModel costModel, boolean aStar) {
        this.costModel = costModel;
        this.aStar = aStar;
        this.search = new ReferenceSearch(costModel, aStar);
    }

    @Override
    public String name() {
        return aStar ? "reference" : "dijkstra";
    }

    @Override
    public PlanResult plan(Costmap costmap, Point2D start, List<Point2D> goals) {
        Optional<PlanResult.Unreachable> problem = PlanRequest.problem(costmap, costModel, start, goals);
        if (problem.isPresent()) {
            return problem.get();
        }
        grid.sync(costmap);
        PlanRequest request = PlanRequest.resolve(grid, start, goals);
        if (!search.search(grid, request.goalCells(), request.startCell())) {
            return PlanRequest.enclosed(search.closedCount());
        }
        int[] cells = search.cellPath(request.startCell());
        double[] points = new double[Math.max(2, cells.length) * 2];
        points[0] = request.startX();
        points[1] = request.startY();
        for (int i = 1; i < cells.length - 1; i++) {
            points[2 * i] = grid.column(cells[i]) + 0.5;
            points[2 * i + 1] = grid.row(cells[i]) + 0.5;
        }
        int goalIndex = 0;
        int goalCell = cells[cells.length - 1];
        for (int i = 0; i < request.goalCells().length; i++) {
            if (request.goalCells()[i] == goalCell) {
                goalIndex = i;
            }
        }
        points[points.length - 2] = request.goalPoints()[2 * goalIndex];
        points[points.length - 1] = request.goalPoints()[2 * goalIndex + 1];
        List<Point2D> waypoints = LpnPlanner.toMap(grid.geometry(), points, start, goals, request.goalPoints());
        PlannedPath path = new PlannedPath(waypoints, CostModel.length(waypoints), costModel.pathCost(costmap, waypoints));
        return new PlanResult.Found(path, new GridField(grid.geometry(), search.costBits(), search.closedCount()));
    }
}
