package sabot.planner.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;

import org.junit.jupiter.api.Test;

import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.map.CellRegion;
import sabot.model.map.Costmap;
import sabot.model.map.GridGeometry;
import sabot.planner.CostModel;
import sabot.planner.TestGrids;

/**
 * The work the navigation function reports ({@link LpnNavigationFunction#expandedCount}, {@code withdrawnCount},
 * {@code deferredCount}): the focused propagation expands an ellipse around a straight path (its bound is 5 % plus a
 * margin above the straight line's cost) with the whole grid's value at the start, and a repair after one new
 * obstacle refills each cell it withdrew once, fewer cells than a computation expands.
 */
class PropagationWorkTest {

    private static final CostModel MODEL = CostModel.standard();

    @Test
    void focusedPropagationExpandsAnEllipseAroundAStraightPathWithTheWholeGridsValue() {
        // start and goal on the middle row: the ellipse (semi-axes about 220 and 100 cells) spans half the rows
        Costmap costmap = Costmap.of(new GridGeometry(400, 400, 1.0, Pose2D.ORIGIN), new byte[400 * 400]);
        Setup setup = new Setup(costmap, new Point2D(5.5, 200.5), new Point2D(394.5, 200.5));
        setup.function.compute(setup.request.goalCells(), -1);
        int whole = setup.function.expandedCount();
        float wholeValue = LpnNavigationFunction.decode(setup.function.potential()[setup.request.startCell()]);
        setup.function.computeFocused(setup.request.goalCells(), setup.request.startCell());
        int focused = setup.function.expandedCount();
        float focusedValue = LpnNavigationFunction.decode(setup.function.potential()[setup.request.startCell()]);
        assertTrue(setup.function.isReached(setup.request.startCell()));
        assertTrue(setup.function.deferredCount() > 0, "cells beside the band are left out");
        assertTrue(focused < whole / 2, "focused " + focused + " of " + whole + " cells");
        assertEquals(wholeValue, focusedValue, 1e-4 * wholeValue);
    }

    @Test
    void aFocusedRePlanToTheSameGoalSkipsTheBoundsThatWereTooSmall() {
        // a wall across the straight line with an opening near the bottom: the path is about 1.6 times the straight
        // line, so the first bounds (5 %, 20 %) do not reach the start
        byte[] cells = new byte[200 * 200];
        for (int row = 0; row <= 180; row++) {
            cells[row * 200 + 100] = (byte) Costmap.LETHAL;
        }
        Costmap costmap = Costmap.of(new GridGeometry(200, 200, 1.0, Pose2D.ORIGIN), cells);
        Setup setup = new Setup(costmap, new Point2D(5.5, 100.5), new Point2D(194.5, 100.5));
        setup.function.computeFocused(setup.request.goalCells(), setup.request.startCell());
        int first = setup.function.expandedCount();
        float firstValue = LpnNavigationFunction.decode(setup.function.potential()[setup.request.startCell()]);
        setup.function.gridChanged(setup.grid, setup.grid.sync(costmap));
        setup.function.computeFocused(setup.request.goalCells(), setup.request.startCell());
        int second = setup.function.expandedCount();
        float secondValue = LpnNavigationFunction.decode(setup.function.potential()[setup.request.startCell()]);
        setup.function.compute(setup.request.goalCells(), -1);
        float wholeValue = LpnNavigationFunction.decode(setup.function.potential()[setup.request.startCell()]);
        assertTrue(second < first * 3 / 4, "re-plan expanded " + second + " cells, the first plan " + first);
        assertEquals(firstValue, secondValue);
        assertEquals(wholeValue, secondValue, 1e-4 * wholeValue);
    }

    @Test
    void aRepairAfterOneObstacleRefillsFewerCellsThanAComputation() {
        Costmap costmap = Costmap.of(new GridGeometry(200, 200, 1.0, Pose2D.ORIGIN), new byte[200 * 200]);
        Setup setup = new Setup(costmap, new Point2D(5.5, 100.5), new Point2D(194.5, 100.5));
        setup.function.compute(setup.request.goalCells(), -1);
        int whole = setup.function.expandedCount();
        assertEquals(0, setup.function.withdrawnCount());
        costmap.set(100, 100, Costmap.LETHAL);
        CellRegion changed = setup.grid.sync(costmap);
        assertTrue(setup.function.repair(setup.grid, changed, setup.request.goalCells()));
        int withdrawn = setup.function.withdrawnCount();
        int refilled = setup.function.expandedCount();
        // on open ground the interpolated values behind the obstacle shift slightly over a wide cone, and the
        // repair withdraws every cell whose value is no longer supported (by more than float rounding)
        assertTrue(withdrawn > 0 && withdrawn < whole / 2, "withdrawn " + withdrawn + " of " + whole);
        assertEquals(withdrawn - 1, refilled, "every withdrawn cell but the obstacle's own is refilled, once");
    }

    @Test
    void landmarksFollowAPoorlyBoundedPlanSurviveARiseAndAreDroppedWhenACostFalls() {
        Costmap costmap = TestGrids.maze(5, 20, false);
        Setup setup = new Setup(costmap, new Point2D(2.5, 2.5),
                new Point2D(costmap.width() - 2.5, costmap.height() - 2.5));
        int[] goals = setup.request.goalCells();
        int start = setup.request.startCell();
        setup.function.computeFocused(goals, start);
        assertFalse(setup.function.hasLandmarks(), "the first plan is bounded by the straight line");
        int straightLine = setup.function.expandedCount();
        setup.function.gridChanged(setup.grid, setup.grid.sync(costmap));
        setup.function.computeFocused(goals, start);
        assertTrue(setup.function.hasLandmarks(), "a maze's path is many times the straight line");
        int byLandmarks = setup.function.expandedCount();
        float value = LpnNavigationFunction.decode(setup.function.potential()[start]);
        assertTrue(byLandmarks < straightLine / 2, byLandmarks + " cells against " + straightLine);
        costmap.set(10, 10, Costmap.LETHAL);
        setup.function.gridChanged(setup.grid, setup.grid.sync(costmap));
        assertTrue(setup.function.hasLandmarks(), "a rise keeps them");
        costmap.set(10, 10, Costmap.FREE);
        setup.function.gridChanged(setup.grid, setup.grid.sync(costmap));
        assertFalse(setup.function.hasLandmarks(), "a fall drops them");
        setup.function.computeFocused(goals, start);
        assertEquals(value, LpnNavigationFunction.decode(setup.function.potential()[start]), 1e-4 * value);
    }

    /** A grid synced from the costmap, a request for start and goal, and a navigation function on both. */
    private static final class Setup {
        final PlanningGrid grid = new PlanningGrid();
        final PlanRequest request;
        final LpnNavigationFunction function = new LpnNavigationFunction(MODEL);

        Setup(Costmap costmap, Point2D start, Point2D goal) {
            CellRegion changed = grid.sync(costmap);
            request = PlanRequest.resolve(grid, start, List.of(goal));
            function.gridChanged(grid, changed);
        }
    }
}
