package sabot.planner.internal;

import java.util.List;
import java.util.Optional;

import sabot.model.geometry.Point2D;
import sabot.model.map.Cell;
import sabot.model.map.Costmap;
import sabot.model.map.GridGeometry;
import sabot.planner.CostModel;
import sabot.planner.PlanResult;
import sabot.planner.UnreachableReason;

/**
 * A planning request checked against the costmap and translated to grid coordinates: what every planner does before
 * searching, so that all of them report bad input the same way.
 *
 * @param startX     start in grid coordinates (cell (c, r) spans [c, c+1) x [r, r+1))
 * @param startY     start in grid coordinates
 * @param startCell  padded index of the start cell
 * @param goalCells  padded indices of the goal cells
 * @param goalPoints goal points in grid coordinates, {x0, y0, x1, y1, ...}
 */
record PlanRequest(double startX, double startY, int startCell, int[] goalCells, double[] goalPoints) {

    /** @return the reason the request cannot be planned, if any */
    static Optional<PlanResult.Unreachable> problem(Costmap costmap, CostModel costModel, Point2D start,
            List<Point2D> goals) {
        if (start == null || !start.isFinite()) {
            return unreachable(UnreachableReason.INVALID_REQUEST, "start " + start + " is not a finite point");
        }
        if (goals == null || goals.isEmpty()) {
            return unreachable(UnreachableReason.INVALID_REQUEST, "the goal set is empty");
        }
        for (Point2D goal : goals) {
            if (goal == null || !goal.isFinite()) {
                return unreachable(UnreachableReason.INVALID_REQUEST, "goal " + goal + " is not a finite point");
            }
        }
        GridGeometry geometry = costmap.geometry();
        Optional<Cell> startCell = geometry.cellAt(start);
        if (startCell.isEmpty()) {
            return unreachable(UnreachableReason.START_OUTSIDE_MAP, "start " + format(start) + " is outside the map "
                    + extent(geometry));
        }
        for (Point2D goal : goals) {
            if (geometry.cellAt(goal).isEmpty()) {
                return unreachable(UnreachableReason.GOAL_OUTSIDE_MAP, "goal " + format(goal) + " is outside the map "
                        + extent(geometry));
            }
        }
        Cell s = startCell.get();
        int startCost = costmap.cost(s.column(), s.row());
        if (!costModel.passable(startCost)) {
            return unreachable(UnreachableReason.START_IN_OBSTACLE, "start " + format(start) + " is in cell ("
                    + s.column() + ", " + s.row() + ") of cost " + startCost + " (" + describe(startCost) + ")");
        }
        for (Point2D goal : goals) {
            Cell g = geometry.cellAt(goal).orElseThrow();
            int goalCost = costmap.cost(g.column(), g.row());
            if (!costModel.passable(goalCost)) {
                return unreachable(UnreachableReason.GOAL_IN_OBSTACLE, "goal " + format(goal) + " is in cell ("
                        + g.column() + ", " + g.row() + ") of cost " + goalCost + " (" + describe(goalCost) + ")");
            }
        }
        return Optional.empty();
    }

    /** @return the request in grid coordinates; call only when {@link #problem} found none */
    static PlanRequest resolve(PlanningGrid grid, Point2D start, List<Point2D> goals) {
        GridGeometry geometry = grid.geometry();
        double sx = geometry.toGridX(start.x());
        double sy = geometry.toGridY(start.y());
        int[] goalCells = new int[goals.size()];
        double[] goalPoints = new double[goals.size() * 2];
        for (int i = 0; i < goals.size(); i++) {
            double gx = geometry.toGridX(goals.get(i).x());
            double gy = geometry.toGridY(goals.get(i).y());
            goalPoints[2 * i] = gx;
            goalPoints[2 * i + 1] = gy;
            goalCells[i] = grid.index((int) gx, (int) gy);
        }
        return new PlanRequest(sx, sy, grid.index((int) sx, (int) sy), goalCells, goalPoints);
    }

    static PlanResult.Unreachable enclosed(int regionCells) {
        return new PlanResult.Unreachable(UnreachableReason.GOAL_ENCLOSED, "no free path joins start and goal: the goal's "
                + "free region (" + regionCells + " cells) does not contain the start");
    }

    private static Optional<PlanResult.Unreachable> unreachable(UnreachableReason reason, String detail) {
        return Optional.of(new PlanResult.Unreachable(reason, detail));
    }

    private static String describe(int cost) {
        return switch (cost) {
            case Costmap.LETHAL -> "lethal obstacle";
            case Costmap.INSCRIBED -> "within the robot's inscribed radius of an obstacle";
            case Costmap.NO_INFORMATION -> "unknown";
            default -> "graded";
        };
    }

    private static String format(Point2D p) {
        return String.format(java.util.Locale.ROOT, "(%.3f, %.3f) m", p.x(), p.y());
    }

    private static String extent(GridGeometry g) {
        return String.format(java.util.Locale.ROOT, "[%.3f, %.3f) x [%.3f, %.3f) m", g.origin().x(),
                g.origin().x() + g.width() * g.resolution(), g.origin().y(), g.origin().y() + g.height() * g.resolution());
    }
}
