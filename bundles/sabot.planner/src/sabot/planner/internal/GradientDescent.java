package sabot.planner.internal;

import sabot.model.map.Costmap;

/**
 * Path extraction: steepest descent on the interpolated navigation function, from the start point to the goal set,
 * in grid coordinates (cell (c, r) spans [c, c+1) x [r, r+1)).
 *
 * <p>Each step moves {@value #STEP} cell against the gradient of N (central differences at the cell centres, blended
 * bilinearly, as navfn does; {@value #STEP} is navfn's {@code pathStep}), and is kept only when the segment crosses passable cells alone and N drops by at least
 * {@value #MIN_DROP_PER_CELL} of the least density per cell moved. Where the gradient is undefined or fails those
 * tests (next to obstacles, in narrow passages) the path moves to the centre of the current cell's lowest
 * neighbour instead, diagonally when both side cells are passable. Every non-goal value was computed from a lower
 * neighbour: an axis neighbour, or a diagonal one through a triangle whose axis cell is passable while the fourth
 * cell of the square may be impassable (the straight diagonal touches its corner). When that diagonal is the only
 * way down, the path takes it past the corner ({@link #pastCorner}). So every segment is collision-free (touching a
 * corner of an impassable cell does not count), N strictly decreases from waypoint to waypoint (one degenerate
 * exception: from a point on the very edge of an impassable cell the path may first move to its cell's centre at
 * equal N), and the descent ends in a goal cell after a bounded number of steps.
 */
public final class GradientDescent {

    /** Step length in cell edges (navfn: {@code pathStep = 0.5}). */
    static final double STEP = 0.5;
    /** Least drop of N per cell moved for a gradient step, as a fraction of the least density. */
    static final double MIN_DROP_PER_CELL = 0.01;
    /** Longest straight shortcut, in cell edges, the smoothing pass tries. */
    static final double MAX_SHORTCUT = 8;

    private static final int[] NEIGHBOUR_DX = { 1, -1, 0, 0, 1, 1, -1, -1 };
    private static final int[] NEIGHBOUR_DY = { 0, 0, 1, -1, 1, -1, 1, -1 };

    private GradientDescent() {
    }

    /**
     * @param potential N by padded index as value bits ({@link LpnNavigationFunction#decode}), 0 on goal cells
     * @param density   density by costmap value ({@code +infinity} impassable)
     * @param goals     goal points as {x0, y0, x1, y1, ...} in grid coordinates; the path ends at the goal whose cell
     *                  it reaches
     * @return waypoints as {x0, y0, x1, y1, ...} in grid coordinates, first the start
     * @throws IllegalStateException when the start is not reached by N or the descent does not end (both are bugs of
     *                               the caller or of N, never a property of the map)
     */
    public static double[] descend(PlanningGrid grid, int[] potential, float[] density, float minDensity,
            double startX, double startY, double[] goals) {
        return descend(grid, potential, density, minDensity, startX, startY, goals, true);
    }

    /**
     * @param freeBoxes false to decide every shortcut by the traversal's sums (the same path, for the test that shows
     *                  it)
     */
    static double[] descend(PlanningGrid grid, int[] potential, float[] density, float minDensity, double startX,
            double startY, double[] goals, boolean freeBoxes) {
        int stride = grid.stride();
        byte[] costs = grid.costs();
        double x = startX;
        double y = startY;
        Descent points = new Descent(new Shortcut(grid, density, freeBoxes));
        points.add(x, y);
        int cell = grid.index((int) x, (int) y);
        if (value(potential, cell) == Float.POSITIVE_INFINITY) {
            throw new IllegalStateException("start cell is not reached by the navigation function");
        }
        double minDrop = MIN_DROP_PER_CELL * minDensity;
        // gradient steps drop N by at least minDrop * STEP / 2; fallback steps visit ever lower cells (and at most
        // once per cell first the cell's own centre, see pastCorner)
        long maxSteps = (long) (value(potential, cell) / (minDrop * STEP / 2)) + 2L * grid.paddedSize() + 16;
        double[] gradient = new double[2];
        Centres centres = new Centres(potential, stride);
        double reached = Double.NaN; // N at (x, y) when the last step was a gradient step, which computed it
        for (long step = 0; ; step++) {
            if (step > maxSteps) {
                throw new IllegalStateException("gradient descent did not reach the goal in " + maxSteps + " steps");
            }
            cell = grid.index((int) x, (int) y);
            if (value(potential, cell) == 0f) {
                finishAtGoal(points, grid, density, goals, x, y);
                break;
            }
            double value = Double.isNaN(reached) ? GridField.interpolate(potential, stride, x, y) : reached;
            reached = Double.NaN;
            boolean moved = false;
            if (gradient(centres, x, y, gradient)) {
                double norm = Math.sqrt(gradient[0] * gradient[0] + gradient[1] * gradient[1]);
                for (double length = STEP; norm > 0 && length >= STEP / 2; length /= 2) {
                    double nx = x - length * gradient[0] / norm;
                    double ny = y - length * gradient[1] / norm;
                    if (nx >= 0 && ny >= 0 && nx < grid.geometry().width() && ny < grid.geometry().height()
                            && passable(grid, density, x, y, nx, ny)) {
                        double next = GridField.interpolate(potential, stride, nx, ny);
                        if (next < value - minDrop * length) {
                            x = nx;
                            y = ny;
                            reached = next;
                            moved = true;
                            break;
                        }
                    }
                }
            }
            if (!moved) {
                int next = lowestNeighbour(grid, costs, potential, density, cell, value, x, y);
                if (next >= 0) {
                    x = grid.column(next) + 0.5;
                    y = grid.row(next) + 0.5;
                } else if (pastCorner(grid, costs, potential, density, cell, value, x, y, gradient)) {
                    x = gradient[0];
                    y = gradient[1];
                } else {
                    throw new IllegalStateException("navigation function has no lower neighbour at cell ("
                            + grid.column(cell) + ", " + grid.row(cell) + "), N " + value(potential, cell)
                            + ", from point (" + x + ", " + y + ") of N " + value);
                }
            }
            points.add(x, y);
        }
        return points.finish();
    }

    /**
     * Drops waypoints where a straight segment from the last kept waypoint costs no more than the path it replaces
     * (line integral of the density) and crosses only passable cells: removes the zig-zag a descent makes across
     * cost valleys without ever raising the path's cost, and keeps N strictly decreasing (only waypoints are removed).
     * Shortcuts are limited to {@value #MAX_SHORTCUT} cells so that the pass stays linear in the path length. The
     * descent's points stream through it as they are made, and only the kept ones are stored (the benchmark maze's
     * descent makes 28,694 points, of which 3,010 are kept). Integrals are the traversal's sums, except where a
     * segment's box is free and its closed form decides ({@link FreeBoxes}): then it stands in for the sum until a
     * close decision needs the sum itself.
     */
    private static final class Shortcut {
        private final GridTraversal.PaddedDensity cells;
        private final Waypoints kept = new Waypoints();
        private final FreeBoxes free;
        private double anchorX;
        private double anchorY;
        private boolean hasPending;
        private double pendingX;
        private double pendingY;
        private double pendingCost;
        /** False while {@link #pendingCost} is the closed form of a free box rather than the traversal's sum. */
        private boolean pendingExact;

        Shortcut(PlanningGrid grid, float[] density, boolean freeBoxes) {
            cells = new GridTraversal.PaddedDensity(grid, density);
            free = freeBoxes ? new FreeBoxes(grid, density) : null;
        }

        /** Takes the path's next point (the first is always kept). */
        void accept(double x, double y) {
            if (kept.size() == 0) {
                kept.add(x, y);
                anchorX = x;
                anchorY = y;
                return;
            }
            if (!hasPending) {
                hasPending = true;
                pendingX = x;
                pendingY = y;
                pendingCost = GridTraversal.integrate(anchorX, anchorY, x, y, cells);
                pendingExact = true;
                return;
            }
            double step = closedForm(pendingX, pendingY, x, y);
            boolean stepExact = Double.isNaN(step);
            if (stepExact) {
                step = GridTraversal.integrate(pendingX, pendingY, x, y, cells);
            }
            double ax = x - anchorX;
            double ay = y - anchorY;
            boolean shortcut;
            if (ax * ax + ay * ay > MAX_SHORTCUT * MAX_SHORTCUT) {
                shortcut = false;
            } else {
                double via = pendingCost + step;
                double closed = closedForm(anchorX, anchorY, x, y);
                // the closed form decides when it is clear of the way via by more than both can differ from the
                // traversal's sums (see FreeBoxes); else, and off free boxes, the traversal's sums decide
                if (closed < via * (1 - FreeBoxes.DECISIVE)) {
                    shortcut = true;
                    pendingCost = closed;
                    pendingExact = false;
                } else if (closed > via * (1 + FreeBoxes.DECISIVE)) {
                    shortcut = false;
                } else {
                    if (!pendingExact) {
                        pendingCost = GridTraversal.integrate(anchorX, anchorY, pendingX, pendingY, cells);
                        pendingExact = true;
                    }
                    if (!stepExact) {
                        step = GridTraversal.integrate(pendingX, pendingY, x, y, cells);
                        stepExact = true;
                    }
                    via = pendingCost + step;
                    // the direct walk stops once it exceeds the way via the pending point: it is then rejected
                    double direct = GridTraversal.integrate(anchorX, anchorY, x, y, cells, via);
                    shortcut = direct <= via;
                    if (shortcut) {
                        pendingCost = direct;
                    }
                }
            }
            if (!shortcut) {
                kept.add(pendingX, pendingY);
                anchorX = pendingX;
                anchorY = pendingY;
                pendingCost = step; // the integral from the new anchor, as computed for the way via it
                pendingExact = stepExact;
            }
            pendingX = x;
            pendingY = y;
        }

        /** The closed form of a free box's integral ({@link FreeBoxes}), or NaN where there is none or it is off. */
        private double closedForm(double x0, double y0, double x1, double y1) {
            return free == null ? Double.NaN : free.integral(x0, y0, x1, y1);
        }

        double[] finish() {
            if (hasPending) {
                kept.add(pendingX, pendingY);
                hasPending = false;
            }
            return kept.toArray();
        }
    }

    /**
     * The integral of a segment whose cells' bounding box is all free: its length times the free density, without the
     * traversal. Only where it is decisive: the traversal sums the segment's pieces cell by cell (at most 2 x
     * {@value GradientDescent#MAX_SHORTCUT} + 2 of them, each product and sum rounded, the crossing parameters
     * accumulated), which differs from the closed form by a few units in the last place (at most 2.3 over 2 M random
     * segments; {@code GradientDescentTest} requires less than a hundredth of {@value #DECISIVE}); so where the closed
     * form and the way via the pending point differ by more than {@value #DECISIVE} of the latter, the traversal's sums
     * would decide the same, and the path is the same point for point ({@code GradientDescentTest} compares both on
     * random grids). Ties (a pending point on the line) and boxes with other cells are left to the traversal.
     */
    static final class FreeBoxes {
        /** Relative difference beyond which the closed form decides a shortcut. */
        static final double DECISIVE = 1e-10;
        /** Shortest segment the closed form is used for (the traversal counts pieces below 1e-9 as points). */
        private static final double MIN_LENGTH = 1e-6;
        private final byte[] runs;
        private final int stride;
        private final int width;
        private final int height;
        private final double freeDensity;

        FreeBoxes(PlanningGrid grid, float[] density) {
            this.runs = grid.freeRuns();
            this.stride = grid.stride();
            this.width = grid.geometry().width();
            this.height = grid.geometry().height();
            this.freeDensity = density[Costmap.FREE];
        }

        /** @return the closed-form integral from (x0, y0) to (x1, y1), or NaN when a cell of its box is not free */
        double integral(double x0, double y0, double x1, double y1) {
            int c0 = (int) Math.floor(Math.min(x0, x1));
            int c1 = (int) Math.floor(Math.max(x0, x1));
            int r0 = (int) Math.floor(Math.min(y0, y1));
            int r1 = (int) Math.floor(Math.max(y0, y1));
            if (c0 < 0 || r0 < 0 || c1 >= width || r1 >= height) {
                return Double.NaN; // the descent's points lie inside the grid; the traversal knows the outside
            }
            int span = c1 - c0;
            for (int i = (r0 + 1) * stride + c0 + 1, end = (r1 + 1) * stride + c0 + 1; i <= end; i += stride) {
                if (runs[i] <= span) {
                    return Double.NaN;
                }
            }
            double dx = x1 - x0;
            double dy = y1 - y0;
            double length = Math.sqrt(dx * dx + dy * dy);
            return length >= MIN_LENGTH ? length * freeDensity : Double.NaN;
        }
    }

    /**
     * The descent's points: the last two are held back, since the end at the goal may replace the last one
     * ({@link #finishAtGoal}); the others go on to the {@link Shortcut}.
     */
    private static final class Descent {
        private final Shortcut shortcut;
        private int size;
        private double previousX;
        private double previousY;
        private double lastX;
        private double lastY;

        Descent(Shortcut shortcut) {
            this.shortcut = shortcut;
        }

        void add(double x, double y) {
            if (size >= 2) {
                shortcut.accept(previousX, previousY);
            }
            previousX = lastX;
            previousY = lastY;
            lastX = x;
            lastY = y;
            size++;
        }

        void setLast(double x, double y) {
            lastX = x;
            lastY = y;
        }

        int size() {
            return size;
        }

        /** The point before the last (needs {@code size() >= 2}). */
        double previousX() {
            return previousX;
        }

        double previousY() {
            return previousY;
        }

        double[] finish() {
            if (size >= 2) {
                shortcut.accept(previousX, previousY);
            }
            shortcut.accept(lastX, lastY);
            return shortcut.finish();
        }
    }

    /** Ends the path at the goal point of the goal cell reached, replacing the entry point when the shortcut is clear. */
    private static void finishAtGoal(Descent points, PlanningGrid grid, float[] density, double[] goals, double x,
            double y) {
        int column = (int) x;
        int row = (int) y;
        for (int i = 0; i < goals.length; i += 2) {
            if ((int) goals[i] == column && (int) goals[i + 1] == row) {
                if (points.size() >= 2
                        && passable(grid, density, points.previousX(), points.previousY(), goals[i], goals[i + 1])) {
                    points.setLast(goals[i], goals[i + 1]);
                } else if (goals[i] != x || goals[i + 1] != y || points.size() == 1) {
                    points.add(goals[i], goals[i + 1]);
                }
                return;
            }
        }
        if (points.size() == 1) {
            points.add(x, y);
        }
    }

    /** A growable list of points as one primitive array (x0, y0, x1, y1, ...). */
    private static final class Waypoints {
        private double[] xy = new double[256];
        private int size;

        void add(double x, double y) {
            if (2 * size + 2 > xy.length) {
                xy = java.util.Arrays.copyOf(xy, xy.length * 2);
            }
            xy[2 * size] = x;
            xy[2 * size + 1] = y;
            size++;
        }

        int size() {
            return size;
        }

        double[] toArray() {
            return java.util.Arrays.copyOf(xy, 2 * size);
        }
    }

    /**
     * Descent direction at (x, y), navfn's way: the normalised central-difference gradient of N at each of the four
     * cell centres around the point, blended bilinearly, so that the direction turns smoothly between cells instead
     * of jumping at cell borders (the gradient of the bilinear interpolation itself is discontinuous there, and makes
     * the path zig-zag in valleys of cost). False when a cell around the point is unreached.
     */
    private static boolean gradient(Centres centres, double x, double y, double[] out) {
        double u = x - 0.5;
        double v = y - 0.5;
        int c0 = (int) Math.floor(u);
        int r0 = (int) Math.floor(v);
        double fu = u - c0;
        double fv = v - r0;
        int i00 = (r0 + 1) * centres.stride + c0 + 1;
        double gx = 0;
        double gy = 0;
        for (int k = 0; k < 4; k++) {
            int slot = centres.slot(i00 + (k & 1) + (k >> 1) * centres.stride);
            if (slot < 0) {
                return false;
            }
            double weight = ((k & 1) == 0 ? 1 - fu : fu) * ((k >> 1) == 0 ? 1 - fv : fv);
            gx += weight * centres.ux[slot];
            gy += weight * centres.uy[slot];
        }
        out[0] = gx;
        out[1] = gy;
        return true;
    }

    /**
     * The normalised gradients of the cell centres a descent has blended last, by cell (a half-cell step mostly keeps
     * the four centres around it, or two of them): a small table indexed by the cell's low bits, so that a centre is
     * computed once while the descent passes it.
     */
    private static final class Centres {
        private static final int SLOTS = 64;
        private final int[] potential;
        private final int stride;
        private final int[] cells = new int[SLOTS];
        private final boolean[] reached = new boolean[SLOTS];
        private final double[] ux = new double[SLOTS];
        private final double[] uy = new double[SLOTS];

        Centres(int[] potential, int stride) {
            this.potential = potential;
            this.stride = stride;
            java.util.Arrays.fill(cells, -1);
        }

        /** @return the slot holding the cell's normalised gradient, or -1 when the cell is unreached */
        int slot(int cell) {
            int slot = cell & (SLOTS - 1);
            if (cells[slot] != cell) {
                cells[slot] = cell;
                float centre = value(potential, cell);
                reached[slot] = centre != Float.POSITIVE_INFINITY;
                if (!reached[slot]) {
                    return -1; // perhaps a cell of the padding ring, whose outer neighbours do not exist
                }
                double dx = difference(value(potential, cell - 1), centre, value(potential, cell + 1));
                double dy = difference(value(potential, cell - stride), centre, value(potential, cell + stride));
                // sqrt rather than Math.hypot: no overflow to guard against here, and hypot (a software routine) made
                // the descent as costly as the navigation function on small grids
                double norm = Math.sqrt(dx * dx + dy * dy);
                ux[slot] = norm > 0 ? dx / norm : 0;
                uy[slot] = norm > 0 ? dy / norm : 0;
            }
            return reached[slot] ? slot : -1;
        }
    }

    /** Central difference of N across a cell, one-sided where a neighbour is unreached. */
    private static double difference(float before, float centre, float after) {
        boolean hasBefore = before != Float.POSITIVE_INFINITY;
        boolean hasAfter = after != Float.POSITIVE_INFINITY;
        if (hasBefore && hasAfter) {
            return 0.5 * (after - before);
        }
        if (hasAfter) {
            return after - centre;
        }
        if (hasBefore) {
            return centre - before;
        }
        return 0;
    }

    /** The reachable neighbour of lowest N below {@code value} whose straight move from (x, y) is clear, or -1. */
    private static int lowestNeighbour(PlanningGrid grid, byte[] costs, int[] potential, float[] density, int cell,
            double value, double x, double y) {
        int stride = grid.stride();
        int best = -1;
        float bestValue = Float.POSITIVE_INFINITY;
        for (int k = 0; k < 8; k++) {
            int dx = NEIGHBOUR_DX[k];
            int dy = NEIGHBOUR_DY[k];
            int next = cell + dx + dy * stride;
            float nextValue = value(potential, next);
            if (!(nextValue < value) || nextValue >= bestValue) {
                continue;
            }
            if (dx != 0 && dy != 0 && (density[costs[cell + dx] & 0xFF] == Float.POSITIVE_INFINITY
                    || density[costs[cell + dy * stride] & 0xFF] == Float.POSITIVE_INFINITY)) {
                continue;
            }
            if (!passable(grid, density, x, y, grid.column(next) + 0.5, grid.row(next) + 0.5)) {
                continue;
            }
            best = next;
            bestValue = nextValue;
        }
        return best;
    }

    /**
     * The move {@link #lowestNeighbour} cannot make: to a diagonal neighbour whose one side cell is impassable. The
     * propagation gives a cell p the value of the straight diagonal from a corner d, {@code N(d) + c sqrt 2}, through
     * the triangle (p, a, d) with a passable axis neighbour a, whatever the fourth cell of the square: the diagonal
     * touches that cell's corner only (see {@link LpnNavigationFunction}). Where the fourth cell is impassable and the
     * costs vary from cell to cell, N(d) may be the only value below N(p) around p (N(a) exceeds N(p) when a costs
     * much more than p), and the diagonal move, which needs both side cells passable, finds nothing. This move
     * follows the propagation instead: the lowest diagonal neighbour d below {@code value} with at least one
     * passable side cell, at d's centre when the straight segment there is clear, else at a point of d on the line
     * from (x, y) through the corner p and d share (that line passes p, the corner point and d alone; the point lies
     * within a quarter cell of the corner, where N interpolates to N(d) as the impassable cell is one of the four
     * centres around it). Last, the centre of the current cell when N there is not above {@code value} (a point
     * between centres may interpolate above it; equal only for a point on the edge of the impassable cell itself),
     * from which the diagonal's segment is clear.
     *
     * @param out receives the point moved to
     * @return false when there is no such move (a bug of N)
     */
    private static boolean pastCorner(PlanningGrid grid, byte[] costs, int[] potential, float[] density, int cell,
            double value, double x, double y, double[] out) {
        int stride = grid.stride();
        int column = grid.column(cell);
        int row = grid.row(cell);
        float bestValue = Float.POSITIVE_INFINITY;
        boolean found = false;
        for (int k = 4; k < 8; k++) {
            int dx = NEIGHBOUR_DX[k];
            int dy = NEIGHBOUR_DY[k];
            int next = cell + dx + dy * stride;
            float nextValue = value(potential, next);
            if (!(nextValue < value) || nextValue >= bestValue) {
                continue;
            }
            if (density[costs[cell + dx] & 0xFF] == Float.POSITIVE_INFINITY
                    && density[costs[cell + dy * stride] & 0xFF] == Float.POSITIVE_INFINITY) {
                continue; // between two impassable cells: no triangle of the propagation passes there
            }
            double centreX = column + dx + 0.5;
            double centreY = row + dy + 0.5;
            if (passable(grid, density, x, y, centreX, centreY)) {
                out[0] = centreX;
                out[1] = centreY;
                bestValue = nextValue;
                found = true;
                continue;
            }
            // the corner shared with d, and the point of d a quarter cell beyond it on the line from (x, y)
            double cornerX = column + (dx > 0 ? 1 : 0);
            double cornerY = row + (dy > 0 ? 1 : 0);
            double ex = cornerX - x;
            double ey = cornerY - y;
            if (!(ex * dx > 0 && ey * dy > 0)) {
                continue; // (x, y) on the cell's edge towards d: no line through the corner alone
            }
            double scale = 0.25 / Math.max(Math.abs(ex), Math.abs(ey));
            double px = cornerX + scale * ex;
            double py = cornerY + scale * ey;
            if (px < 0 || py < 0 || grid.index((int) px, (int) py) != next
                    || !(GridField.interpolate(potential, stride, px, py) < value)
                    || !passable(grid, density, x, y, px, py)) {
                continue;
            }
            out[0] = px;
            out[1] = py;
            bestValue = nextValue;
            found = true;
        }
        if (found) {
            return true;
        }
        // (x, y) between centres whose interpolation lies above N here; or, N equal, a point on the very edge of the
        // impassable side cell, from where no line passes the corner alone: from the centre the diagonal's is clear
        float own = value(potential, cell);
        if (own <= value && (x != column + 0.5 || y != row + 0.5)) {
            out[0] = column + 0.5;
            out[1] = row + 0.5;
            return true;
        }
        return false;
    }

    private static float value(int[] potential, int index) {
        return LpnNavigationFunction.decode(potential[index]);
    }

    /** True when the segment crosses only passable cells (touching a corner does not count). */
    static boolean passable(PlanningGrid grid, float[] density, double x0, double y0, double x1, double y1) {
        int c0 = (int) Math.floor(Math.min(x0, x1));
        int r0 = (int) Math.floor(Math.min(y0, y1));
        int c1 = (int) Math.floor(Math.max(x0, x1));
        int r1 = (int) Math.floor(Math.max(y0, y1));
        if (c1 - c0 <= 1 && r1 - r0 <= 1 && c0 >= -1 && r0 >= -1 && c1 <= grid.geometry().width()
                && r1 <= grid.geometry().height()) {
            // a short segment (a descent step) lies in the 2 x 2 cells of its bounding box: when all of them are
            // passable, so is the segment, without the traversal (the common case away from obstacles)
            byte[] costs = grid.costs();
            int stride = grid.stride();
            int i00 = (r0 + 1) * stride + c0 + 1;
            byte[] runs = grid.freeRuns();
            // both rows' free runs cover the box: all free, so passable (two loads instead of the eight below)
            if (runs[i00] > c1 - c0 && runs[(r1 + 1) * stride + c0 + 1] > c1 - c0) {
                return true;
            }
            int i11 = (r1 + 1) * stride + c1 + 1;
            int i01 = (r1 + 1) * stride + c0 + 1;
            int i10 = (r0 + 1) * stride + c1 + 1;
            if (density[costs[i00] & 0xFF] != Float.POSITIVE_INFINITY
                    && density[costs[i11] & 0xFF] != Float.POSITIVE_INFINITY
                    && density[costs[i01] & 0xFF] != Float.POSITIVE_INFINITY
                    && density[costs[i10] & 0xFF] != Float.POSITIVE_INFINITY) {
                return true;
            }
        }
        return GridTraversal.integrate(x0, y0, x1, y1, new GridTraversal.PaddedDensity(grid, density))
                != Double.POSITIVE_INFINITY;
    }
}
