package sabot.planner.internal;

import java.util.Arrays;

import sabot.model.map.CellRegion;
import sabot.planner.CostModel;

/**
 * Konolige's LPN navigation function (K. Konolige, "A gradient method for realtime robot control", IROS 2000) over a
 * {@link PlanningGrid}: every goal cell holds 0, every other reachable cell p the least cost to the goal set,
 *
 * <pre>
 *   N(p) = min over neighbours q of  N(q) + |p - q| * c,   c = (h(p) + h(q)) / 2       (8 neighbours, CostModel)
 * </pre>
 *
 * refined by interpolation so that values are not tied to the eight grid directions: the wave may cross between an
 * axis neighbour a and the adjacent diagonal neighbour d at any point ({@link InterpolatedUpdate}, after Tsitsiklis;
 * the same idea as navfn's quadratic update, on eight neighbours).
 *
 * <p>Expanding a final cell a updates its four axis neighbours p through both triangles (p, a, d). There is no
 * separate diagonal update: the straight diagonal step from d is the t = 1 end of a triangle, evaluated when a is
 * expanded. The corner d is read as stored, whether popped yet or not: if N(d) &lt; N(a) then d lies in the current
 * or an earlier bucket, where values are already final (below); a higher corner cannot lower the result. (A diagonal
 * step is missed only when both cells beside it are so costly that they are expanded after p; p then keeps an upper
 * bound, the cost of a real path. The diagonal end of a triangle passes through the corner point shared with the
 * fourth cell of the square, which the robot's centre may touch, never cross.)
 *
 * <p>Priority scheme: every update raises N by at least {@code c_min / sqrt(2)} over the values it reads
 * ({@code c_min} = {@link CostModel#minDensity()}), so with buckets of that width (R. Dial, CACM 12(11), 1969) all
 * cells in the lowest non-empty bucket are final and can be expanded in any order: each cell is expanded once, in
 * O(1) per queue operation, and never revisited. Buckets form a ring because no update reaches further than
 * {@code sqrt(2) * c_max} ahead.
 *
 * <p>Storage: one {@code int} per padded cell holds the IEEE bits of N (for non-negative floats the bit patterns order
 * like the values, so they compare as ints) with the sign bit set once the value is final. Impassable cells are
 * stored as final {@code +infinity}, so one load and one sign test reject both final and impassable neighbours.
 * The loops allocate nothing once the buckets have grown to the map's wavefront size.
 *
 * <p>Three ways to compute N, for three questions: {@link #compute} over the whole reachable grid (a field for every
 * start, and the base a repair needs); {@link #computeFocused} only as far as a plan from one start needs it, bounded
 * by the straight line or, on grids where paths are many times longer (a maze), by landmarks
 * ({@link LandmarkBound}); and {@link #repair} of a whole-grid field after costs rose ({@link NavigationRepair}).
 * All three share one propagation loop ({@link #expandRange}), tuned for C2: it stays one compiled method with the
 * per-cell work inlined, without branches on the data where the outcome is a coin toss.
 */
public final class LpnNavigationFunction implements AutoCloseable {

    /** Bits of an unreached passable cell: +infinity, not final. */
    public static final int UNREACHED = 0x7F800000;
    /** Bits of an impassable cell: +infinity, final. */
    public static final int IMPASSABLE = 0xFF800000;
    static final int FINAL = 0x80000000;

    static final int VALUE = 0x7FFFFFFF;

    private static final float SQRT2 = InterpolatedUpdate.SQRT2;
    private static final float INV_SQRT2 = InterpolatedUpdate.INV_SQRT2;
    /** Bucket width as a fraction of the least increment, a margin for float rounding. */
    private static final float BUCKET_MARGIN = 0.99f;

    private static final int INITIAL_BUCKET_CAPACITY = 1024;
    /** Most cells one expansion queues: its four axis neighbours. */
    private static final int PUSHES_PER_CELL = 4;
    /** Most cells one expansion of a repair queues: its own four and those of four re-expanded neighbours. */
    private static final int PUSHES_PER_REPAIRED_CELL = 20;
    /**
     * First excess of the focused propagation's bound over c_min times the straight distance from the start to the
     * nearest goal (see {@link #computeFocused}): 5 %; random grids between opposite corners need 4 %.
     */
    static final float FOCUS_FIRST_EXCESS = 0.05f;
    /** Factor of the excess from one focused attempt to the next. */
    private static final float FOCUS_GROWTH = 4f;
    /**
     * A second or later focused attempt that expanded more than this fraction of the grid in vain is followed by an
     * unfocused one.
     */
    private static final int FOCUS_GIVE_UP_FRACTION = 32;
    /** Reached cells are recorded for the reset up to this fraction of the grid (see {@link #touched}). */
    private static final int TOUCHED_FRACTION = 8;

    private final float[] density;
    /** Half of {@link #density}: the edge density between two cells is the sum of their halves. */
    private final float[] halfDensity;
    private final float maxDensity;
    /**
     * At least the highest density of a passable cell of the grid (the cost model's highest where a graded cell of
     * that cost is present; c_min on a grid of free and lethal cells only): the focus's margin is counted in it.
     * Raised by changes, never lowered until the grid is replaced (too high only widens the margin).
     */
    private float gridMaxDensity;
    private final float bucketWidth;
    private final float inverseBucketWidth;
    /** Mask of the bucket ring (its size is a power of two). */
    private final int bucketMask;
    /**
     * The bucket ring, flat: bucket slot s holds its cells at {@code [s << bucketShift, s << bucketShift + size)} (one
     * array rather than one per bucket: one load less per push and per pop in the hot loop); all buckets grow together.
     */
    private int[] buckets;
    private int bucketShift;
    private final int[] bucketSizes;
    /**
     * At least the largest {@link #bucketSizes} entry: room in the ring is made before a bucket is expanded (see
     * {@link #makeRoom}) from this bound, which is recomputed exactly only when it says the ring may be too small.
     */
    private int fillBound;
    private final float minDensity;

    private PlanningGrid grid;
    private int[] potential = new int[0];
    /** N as a computation starts: {@link #UNREACHED} or {@link #IMPASSABLE} per cell, kept in step with the grid. */
    private int[] initialPotential = new int[0];
    /**
     * Cells reached since the last reset, as long as they fit: a computation that reaches more (most of the grid)
     * stops recording them and is undone by copying {@link #initialPotential} whole, which is cheaper.
     */
    private int[] touched = new int[0];
    /** Goals of the last complete computation (whole reachable grid), or null: what {@link #repair} builds on. */
    private int[] completeGoals;
    private int touchedCount;
    private int finalizedCount;
    /**
     * Focus of the propagation: a cell p is expanded only if {@code N(p) + c_min |p - start| <= focusBound}
     * ({@code +infinity}: every cell); cells outside are deferred (reached, not expanded) and counted in
     * {@link #deferred}. Start row and column in cells.
     */
    private float focusBound = Float.POSITIVE_INFINITY;
    /**
     * Goals of the last focused computation that reached its start, and the excess of its successful attempt
     * ({@code +infinity}: unfocused); the next focused computation to the same goals starts from it. Forgotten
     * with the grid.
     */
    private int[] focusGoals;
    private float focusExcess;
    private int focusRow;
    private int focusColumn;
    /** Excess of the last successful landmark-bounded computation to {@link #focusGoals}. */
    private float landmarkExcess;
    /** The landmarks' lower bound, built on grids where the straight line bounds poorly; see {@link LandmarkBound}. */
    private final LandmarkBound landmarks = new LandmarkBound();
    /** Whether the running focused computation bounds with {@link #landmarks} instead of the straight line. */
    private boolean focusByLandmarks;
    /** The repair after costs rose: its checks, seeds and withdrawn cells; see {@link NavigationRepair}. */
    private final NavigationRepair riseRepair;
    private int deferred;
    /** Expansions of the last computation or repair (every attempt of a focused one); cells a repair withdrew. */
    private int expandedCount;
    private int withdrawnCount;
    private int queued;
    private int currentBucket;
    /** The order of large buckets' cells, sized for the grid. */
    private MemoryBandOrder bandOrder = new MemoryBandOrder(0);
    /** The running computation's stop (see {@link #propagate}) and the counts of its ranges ({@link #expandRange}). */
    private float stopAbove;
    private int rangeFinalized;
    private int rangeDeferred;

    /** A navigation function computed on the calling thread. */
    public LpnNavigationFunction(CostModel costModel) {
        this(costModel, 1);
    }

    /**
     * @param threads 1 or 2, both computed on the calling thread: a helper thread would have to meet the propagation
     *                at every bucket hand-over (some 2,000 per computation on 1000 x 1000), by spinning, which stalls
     *                whenever another process shares the CPU, or by a wake-up each, which costs more than it saves;
     *                2 is accepted so that configurations asking for it keep working
     */
    public LpnNavigationFunction(CostModel costModel, int threads) {
        if (threads < 1 || threads > 2) {
            throw new IllegalArgumentException("threads must be 1 or 2, not " + threads);
        }
        this.density = costModel.densityTable();
        this.halfDensity = new float[density.length];
        for (int i = 0; i < density.length; i++) {
            halfDensity[i] = 0.5f * density[i];
        }
        this.maxDensity = costModel.maxDensity();
        this.bucketWidth = BUCKET_MARGIN * costModel.minDensity() * INV_SQRT2;
        this.inverseBucketWidth = 1f / bucketWidth;
        int reach = (int) Math.ceil(SQRT2 * costModel.maxDensity() / bucketWidth) + 2;
        this.minDensity = costModel.minDensity();
        this.bucketMask = (Integer.highestOneBit(reach + 1) << 1) - 1;
        int ring = bucketMask + 1;
        this.bucketShift = Integer.numberOfTrailingZeros(Math.max(64, INITIAL_BUCKET_CAPACITY * 16 / ring));
        this.buckets = new int[ring << bucketShift];
        this.bucketSizes = new int[ring];
        this.riseRepair = new NavigationRepair(density);
    }

    /** Nothing to end: computations run on the calling thread (kept so that callers may close every planner). */
    @Override
    public void close() {
    }

    /** @return the value of stored bits: N in cost units, {@code +infinity} for unreached or impassable cells */
    public static float decode(int bits) {
        return Float.intBitsToFloat(bits & VALUE);
    }

    /** @return N by padded index as stored bits (see {@link #decode}); valid until the next computation */
    public int[] potential() {
        return potential;
    }

    /** @return number of cells holding a final value after the last computation */
    public int finalizedCount() {
        return finalizedCount;
    }

    /** @return true when the cell holds a final, finite value */
    public boolean isReached(int index) {
        int bits = potential[index];
        return bits < 0 && bits != IMPASSABLE;
    }

    /**
     * Takes note of changed cells of the grid (after {@link PlanningGrid#sync}); must be called for every change
     * between computations.
     */
    public void gridChanged(PlanningGrid planningGrid, CellRegion changed) {
        completeGoals = null;
        if (planningGrid != grid || potential.length != planningGrid.paddedSize()) {
            grid = planningGrid;
            focusGoals = null;
            landmarks.drop();
            potential = new int[planningGrid.paddedSize()];
            initialPotential = new int[planningGrid.paddedSize()];
            touched = new int[planningGrid.paddedSize() / TOUCHED_FRACTION + 16];
            touchedCount = 0;
            bandOrder = new MemoryBandOrder(planningGrid.paddedSize());
            byte[] costs = planningGrid.costs();
            gridMaxDensity = minDensity;
            for (int i = 0; i < potential.length; i++) {
                takeCell(i, costs);
            }
            return;
        }
        resetTouched();
        byte[] costs = planningGrid.costs();
        for (int row = changed.minRow(); row <= changed.maxRow(); row++) {
            int from = planningGrid.index(changed.minColumn(), row);
            int to = planningGrid.index(changed.maxColumn(), row);
            if (landmarks.watchesCostFalls()) {
                for (int column = changed.minColumn(); column <= changed.maxColumn(); column++) {
                    int before = planningGrid.previousCost(column, row);
                    if (before < 0 || density[costs[from + column - changed.minColumn()] & 0xFF] < density[before]) {
                        landmarks.drop(); // a cheaper cell can shorten paths: the bounds may exceed the new costs
                        break;
                    }
                }
            }
            for (int i = from; i <= to; i++) {
                takeCell(i, costs);
            }
        }
    }

    /** Takes a cell's cost from the grid: its density, its initial N and the grid's highest density. */
    private void takeCell(int i, byte[] costs) {
        float d = density[costs[i] & 0xFF];
        initialPotential[i] = d == Float.POSITIVE_INFINITY ? IMPASSABLE : UNREACHED;
        potential[i] = initialPotential[i];
        if (d > gridMaxDensity && d != Float.POSITIVE_INFINITY) {
            gridMaxDensity = d;
        }
    }

    /**
     * Computes N over everything reachable from the goal cells.
     *
     * @param goals      padded indices of passable goal cells
     * @param stopAtCell padded index after whose value (plus a margin of two diagonal steps) the computation may
     *                   stop, or -1 for the whole reachable grid
     */
    public void compute(int[] goals, int stopAtCell) {
        completeGoals = stopAtCell < 0 ? goals.clone() : null;
        expandedCount = 0;
        withdrawnCount = 0;
        focusBound = Float.POSITIVE_INFINITY;
        start(goals);
        propagate(stopAtCell, false);
    }

    /** Clears the previous computation and queues the goal cells at 0. */
    private void start(int[] goals) {
        riseRepair.clear();
        resetTouched();
        finalizedCount = 0;
        queued = 0;
        deferred = 0;
        currentBucket = 0;
        Arrays.fill(bucketSizes, 0);
        fillBound = 0;
        for (int goal : goals) {
            if (potential[goal] == UNREACHED) {
                if (touchedCount < touched.length) {
                    touched[touchedCount] = goal;
                }
                touchedCount++;
                potential[goal] = 0;
                push(goal, 0f);
            }
        }
    }

    /**
     * Computes N from the goal cells as far as a plan from {@code startCell} needs it: {@link #compute} stopped at
     * the start, expanding only cells that can lie on a path from the start of cost at most a bound U, i.e. with
     * {@code N(p) + c_min |p - start| <= U + margin} (c_min |p - start| is a lower bound of the cost from p to the
     * start, as A*'s heuristic; P. E. Hart, N. J. Nilsson, B. Raphael, IEEE SSC 4(2), 1968). Cells are still expanded
     * in increasing N, so every expanded cell is final and expanded once, with the values of the whole-grid
     * propagation (to the order effects inside a bucket, see the class comment): the bound only leaves out cells
     * (deferred: reached, not expanded), no cell is expanded twice as in A* with this update (whose keys N + h fall
     * along many updates: the interpolated update may raise N by only c / sqrt 2 while h falls by c_min). The
     * margin, four diagonal steps at the highest density, covers the corners of the triangles of the path's cells
     * (their keys exceed the path's by less than c_min sqrt 2) and the neighbourhood the descent reads.
     *
     * <p>U starts at c_min times the straight distance to the nearest goal plus {@link #FOCUS_FIRST_EXCESS}; when the
     * start is not reached within it and cells were deferred, the excess grows fourfold and the computation starts
     * again, without a bound once a second or later attempt has expanded a 32nd of the grid in vain (the region
     * grows steeply with U, so a tight first bound pays more than the occasional repeated computation).
     * A computation to the same goals as the last one that reached its start begins with that one's final excess
     * (a robot re-planning on its way to a goal pays the vain attempts once; the excess is not lowered again until
     * the goals or the grid change).
     * When no cell was deferred the region of the goals was exhausted: the start is unreachable, as for
     * {@link #compute}.
     *
     * <p>Where the straight line bounds poorly (plans needed an excess of {@link LandmarkBound#WANTED_EXCESS} or more:
     * a maze, whose paths are many times the straight line, so that the focus excluded nothing), the next focused
     * computation on the same grid first builds {@link LandmarkBound landmarks}, and from then on the focus uses their
     * lower bound instead of the straight line, with U starting {@link LandmarkBound#FIRST_EXCESS} above that bound at
     * the goal. The landmarks are kept while costs only rise (every plan of a robot whose sonar adds obstacles) and
     * dropped when a cost falls or the grid is replaced.
     *
     * @param goals     padded indices of passable goal cells
     * @param startCell padded index of the start
     */
    public void computeFocused(int[] goals, int startCell) {
        if (landmarks.isDue()) {
            landmarks.build(this, goals[0]);
        }
        completeGoals = null;
        expandedCount = 0;
        withdrawnCount = 0;
        int stride = grid.stride();
        focusRow = startCell / stride;
        focusColumn = startCell - focusRow * stride;
        double distance = Double.POSITIVE_INFINITY;
        for (int goal : goals) {
            distance = Math.min(distance, Math.hypot(goal % stride - focusColumn, goal / stride - focusRow));
        }
        double lowerBound = minDensity * distance;
        boolean disconnected = false;
        focusByLandmarks = landmarks.activate(goals, startCell);
        if (focusByLandmarks) {
            float nearest = landmarks.nearestGoalBound(goals);
            lowerBound = Math.max(lowerBound, nearest == Float.POSITIVE_INFINITY ? 0 : nearest);
            // no goal is connected to a landmark the start is connected to: none is connected to the start (costs
            // only rose since the landmarks were computed, and a rise never joins regions), so the goals' region is
            // exhausted without a bound and reported as for an unfocused computation
            disconnected = nearest == Float.POSITIVE_INFINITY;
        }
        // four diagonal steps at the highest density: with fewer the descent can read deferred cells' values and
        // take a dearer path than the whole grid's; the highest density of the grid's own cells, not the cost
        // model's: on a grid of free and lethal cells (a maze) a diagonal step costs c_min sqrt 2, and the cost
        // model's highest density would make the margin five times wider
        float margin = 4 * SQRT2 * gridMaxDensity;
        // a robot re-plans to the same goal as it moves: an excess that was too small last time is skipped
        boolean sameGoals = Arrays.equals(goals, focusGoals);
        float excess = sameGoals ? (focusByLandmarks ? landmarkExcess : focusExcess)
                : focusByLandmarks ? LandmarkBound.FIRST_EXCESS : FOCUS_FIRST_EXCESS;
        if (disconnected) {
            excess = Float.POSITIVE_INFINITY;
        }
        int vainAttempts = 0;
        while (true) {
            focusBound = excess == Float.POSITIVE_INFINITY ? Float.POSITIVE_INFINITY
                    : (float) (lowerBound * (1 + excess)) + margin;
            start(goals);
            propagate(startCell, false);
            if (isReached(startCell) || deferred == 0) {
                break;
            }
            vainAttempts++;
            // a second vain attempt that already expanded a sizeable part of the grid (a maze, where paths are many
            // times the straight distance) is followed by the unfocused propagation rather than more attempts; after
            // the first the bound is raised in any case, as on the robot's lab map that expands fewer cells in all
            // than giving up after the first
            excess = vainAttempts >= 2 && finalizedCount > potential.length / FOCUS_GIVE_UP_FRACTION
                    ? Float.POSITIVE_INFINITY
                    : excess * FOCUS_GROWTH;
        }
        if (isReached(startCell)) {
            if (!sameGoals) {
                focusGoals = goals.clone();
                focusExcess = FOCUS_FIRST_EXCESS;
                landmarkExcess = LandmarkBound.FIRST_EXCESS;
            }
            if (focusByLandmarks) {
                landmarkExcess = excess;
            } else {
                focusExcess = excess;
                landmarks.noteStraightLineExcess(excess);
            }
        }
        focusBound = Float.POSITIVE_INFINITY;
        focusByLandmarks = false;
    }

    /** @return whether focused computations bound with landmarks (built after poorly bounded plans on this grid) */
    boolean hasLandmarks() {
        return landmarks.isBuilt();
    }

    /**
     * @return cells expanded by the last {@link #compute}, {@link #computeFocused} (all its attempts) or
     *         {@link #repair} (the withdrawn cells refilled and the cells their new values lowered): the work done
     */
    public int expandedCount() {
        return expandedCount;
    }

    /** @return cells whose values the last {@link #repair} withdrew (0 after a computation) */
    public int withdrawnCount() {
        return withdrawnCount;
    }

    /**
     * @return number of times the last computation left a popped cell out by its focus (see {@link #computeFocused}):
     *         the cells left out, a cell lowered after it was left out counted again
     */
    public int deferredCount() {
        return deferred;
    }

    /**
     * Repairs N after costs rose in {@code changed} (already synced into the grid), instead of recomputing it (see
     * {@link NavigationRepair}): the values the change no longer supports are withdrawn, re-seeded from their valid
     * neighbours and refilled by the ordinary propagation. Work is proportional to the cells whose value depended on
     * the change (the "shadow" behind a new obstacle), not to the grid.
     *
     * @return false, changing nothing, when a repair is not possible and {@link #gridChanged} plus {@link #compute}
     *         must be used: no complete computation for these goals, a change too large to have been remembered, or
     *         a cost that fell (a lower cost can shorten paths anywhere behind it)
     */
    public boolean repair(PlanningGrid planningGrid, CellRegion changed, int[] goals) {
        if (planningGrid != grid || completeGoals == null || !Arrays.equals(completeGoals, goals)) {
            return false;
        }
        expandedCount = 0;
        withdrawnCount = 0;
        if (changed.isEmpty()) {
            return true;
        }
        float highest = riseRepair.highestDensityAfterRise(grid, changed, gridMaxDensity);
        if (highest < 0) {
            return false;
        }
        gridMaxDensity = highest;
        int withdrawn = riseRepair.withdraw(grid, changed, potential, initialPotential);
        finalizedCount -= withdrawn;
        withdrawnCount = withdrawn;
        if (withdrawn == 0) {
            return true;
        }
        queued = 0;
        Arrays.fill(bucketSizes, 0);
        fillBound = 0;
        currentBucket = riseRepair.seed(grid, potential, inverseBucketWidth);
        if (currentBucket != Integer.MAX_VALUE) {
            propagate(-1, true);
        }
        riseRepair.forgetCutOff(potential);
        return true;
    }

    /**
     * Moves repair seeds whose bucket the ring can hold into it; when the ring is empty, first advances to the
     * lowest seed's bucket.
     */
    private void injectSeeds() {
        if (queued == 0) {
            currentBucket = Math.max(currentBucket, (int) (riseRepair.lowestSeed() * inverseBucketWidth));
        }
        int horizon = currentBucket + bucketMask;
        while (riseRepair.hasSeeds() && (int) (riseRepair.lowestSeed() * inverseBucketWidth) < horizon) {
            float seed = riseRepair.lowestSeed();
            int cell = riseRepair.popSeed();
            int bits = potential[cell];
            if (bits >= 0 && Float.floatToRawIntBits(seed) < bits) {
                potential[cell] = Float.floatToRawIntBits(seed);
                push(cell, seed);
            }
        }
    }

    private void resetTouched() {
        if (touchedCount > touched.length) {
            System.arraycopy(initialPotential, 0, potential, 0, potential.length);
        } else {
            for (int i = 0; i < touchedCount; i++) {
                potential[touched[i]] = initialPotential[touched[i]];
            }
        }
        touchedCount = 0;
    }

    private void propagate(int stopAtCell, boolean repairing) {
        final int stride = grid.stride();
        stopAbove = Float.POSITIVE_INFINITY;
        // below this N a cell lies inside the focus wherever it is (c_min |p - start| is at most c_min times the
        // grid's diagonal); +infinity without a focus, so that the whole-grid loop pays one predictable comparison
        final float focusFrom = focusBound - Math.max(minDensity * (float) Math.hypot(stride, potential.length / stride),
                focusByLandmarks ? landmarks.boundReach() : 0f);
        final double inverseStride = 1.0 / stride;
        rangeFinalized = 0;
        rangeDeferred = 0;
        while ((queued > 0 || riseRepair.hasSeeds()) && currentBucket * bucketWidth <= stopAbove) {
            if (riseRepair.hasSeeds()) {
                injectSeeds();
                if (queued == 0) {
                    continue;
                }
            }
            int slot = currentBucket & bucketMask;
            if (bandOrder.isWorthSorting(bucketSizes[slot])) {
                bandOrder.sort(buckets, slot << bucketShift, bucketSizes[slot], 1 << bucketShift);
            }
            int head = 0;
            // cells may be queued into the bucket being expanded (one lowered by the straight diagonal from a low
            // corner lands at or below the current bucket; a repair's re-expansions): expand it again up to its new end
            for (int end = bucketSizes[slot]; head < end; end = bucketSizes[slot]) {
                makeRoom((end - head) * (repairing ? PUSHES_PER_REPAIRED_CELL : PUSHES_PER_CELL));
                int pushed = expandRange(slot, head, end, stopAtCell, repairing, focusFrom, inverseStride);
                fillBound += pushed;
                queued += pushed;
                head = end;
            }
            queued -= head;
            bucketSizes[slot] = 0;
            currentBucket++;
        }
        finalizedCount += rangeFinalized;
        expandedCount += rangeFinalized;
        deferred += rangeDeferred;
        // cells reached but not final when a bounded computation stops are still queued: record them for the reset
        for (int slot = 0; queued > 0 && slot <= bucketMask; slot++) {
            for (int i = 0; i < bucketSizes[slot]; i++) {
                if (touchedCount < touched.length) {
                    touched[touchedCount] = buckets[(slot << bucketShift) + i];
                }
                touchedCount++;
            }
            queued -= bucketSizes[slot];
        }
    }

    /**
     * Expands the entries {@code [head, end)} of the current bucket's slot: the hot loop, a method of its own (too
     * large for C2 to inline into {@link #propagate}) so that C2 compiles it from its own profile, apart from the
     * per-bucket work of {@link #propagate} (the memory-band sort, the ring's growth, seeds), whose branches are first
     * taken in the middle of a computation: in one method, such a branch would be an uncommon trap of the compiled
     * loop, and the loop recompiled after it from a profile of the computation's start runs slower. The price is a
     * call per bucket.
     *
     * @return the cells queued
     */
    private int expandRange(int slot, int head, int end, int stopAtCell, boolean repairing, float focusFrom,
            double inverseStride) {
        final int[] potential = this.potential;
        final float[] halfDensity = this.halfDensity;
        final byte[] costs = grid.costs();
        final int stride = grid.stride();
        // the ring cannot grow while the bucket is expanded ({@link #makeRoom} runs before), so its array and shift
        // are loop invariants in registers: with a growth call inside the loop C2 would reload them at every update
        final int[] buckets = this.buckets;
        final int shift = bucketShift;
        final int current = currentBucket;
        final int[] touched = this.touched;
        final int lastTouched = touched.length - 1;
        // counters in locals, written back after the range: fields would be loaded and stored on every update
        // (C2 keeps no field in a register across a loop), a chain of store-to-load forwarding through the loop
        int pushed = 0;
        int record = touchedCount;
        int finalized = 0;
        int deferredHere = 0;
        for (; head < end; head++) {
            int cell = buckets[(slot << shift) + head];
            int bits = potential[cell];
            if (bits < 0) {
                continue;
            }
            // recorded without a branch: the list overflows once a computation has reached an eighth of the grid, so
            // a branch on the overflow would be an uncommon trap of the loop compiled earlier (see above). Past the
            // end the last slot is overwritten; an overflowed list is not read (resetTouched copies the grid)
            touched[Math.min(record, lastTouched)] = cell;
            record++;
            float value = Float.intBitsToFloat(bits);
            if (value > focusFrom && outsideFocus(cell, value, stride, inverseStride)) {
                deferredHere++; // reached (recorded for the reset), left out
                continue;
            }
            potential[cell] = bits | FINAL;
            finalized++;
            if (cell == stopAtCell) {
                stopAbove = value + 2 * SQRT2 * maxDensity;
            }
            // expand(cell, ...) written out: the hot loop stays one compiled method with relax inlined
            float ownHalfDensity = halfDensity[costs[cell] & 0xFF];
            int eastBits = potential[cell + 1];
            int westBits = potential[cell - 1];
            int northBits = potential[cell + stride];
            int southBits = potential[cell - stride];
            float northSouthCorner = InterpolatedUpdate.lower(northBits, southBits);
            float eastWestCorner = InterpolatedUpdate.lower(eastBits, westBits);
            if (eastBits >= 0) {
                pushed += relax(cell + 1, eastBits, value, northSouthCorner, ownHalfDensity, halfDensity, costs,
                        buckets, shift, current);
            }
            if (westBits >= 0) {
                pushed += relax(cell - 1, westBits, value, northSouthCorner, ownHalfDensity, halfDensity, costs,
                        buckets, shift, current);
            }
            if (northBits >= 0) {
                pushed += relax(cell + stride, northBits, value, eastWestCorner, ownHalfDensity, halfDensity, costs,
                        buckets, shift, current);
            }
            if (southBits >= 0) {
                pushed += relax(cell - stride, southBits, value, eastWestCorner, ownHalfDensity, halfDensity, costs,
                        buckets, shift, current);
            }
            if (repairing) {
                // a repaired cell is also the corner of triangles through its final axis neighbours, which a
                // fresh computation would expand after it: let them see its new value
                pushed += reexpand(cell + 1, value, potential, costs, stride);
                pushed += reexpand(cell - 1, value, potential, costs, stride);
                pushed += reexpand(cell + stride, value, potential, costs, stride);
                pushed += reexpand(cell - stride, value, potential, costs, stride);
            }
        }
        touchedCount = record;
        rangeFinalized += finalized;
        rangeDeferred += deferredHere;
        return pushed;
    }

    /**
     * @return true when a cell of value {@code value} lies outside the focus, {@code N + c_min |p - start| > focusBound}
     *         or, with landmarks, {@code N + landmarkBound(p) > focusBound} instead
     */
    private boolean outsideFocus(int cell, float value, int stride, double inverseStride) {
        if (focusByLandmarks) {
            // the straight line is not checked as well: where landmarks are used it bounds far less
            return value + landmarks.bound(cell) > focusBound;
        }
        // row = cell / stride without a division: (cell + 0.5) / stride lies strictly inside (row, row + 1)
        int row = (int) ((cell + 0.5) * inverseStride);
        float dx = cell - row * stride - focusColumn;
        float dy = row - focusRow;
        float reach = (focusBound - value) / minDensity;
        return reach < 0 || dx * dx + dy * dy > reach * reach;
    }

    /** Relaxes the axis neighbours of a final cell {@code axis} again if it lies above {@code value}; returns the cells queued. */
    private int reexpand(int axis, float value, int[] potential, byte[] costs, int stride) {
        int bits = potential[axis];
        if (bits >= 0 || bits == IMPASSABLE || decode(bits) <= value) {
            return 0;
        }
        return expand(axis, decode(bits), halfDensity[costs[axis] & 0xFF], potential, halfDensity, costs, stride);
    }

    /**
     * Updates the four axis neighbours of a final cell (value {@code value}, half density {@code ownHalfDensity}).
     * A target's two diagonal corners next to the cell are the cell's other axis neighbours, so the four neighbours
     * are loaded once: east and west share the corner min(N(north), N(south)), north and south min(N(east), N(west)).
     * Reading a corner before a sibling update lowered it gives the same result: a value this expansion writes lies
     * above {@code value}, and a corner above {@code value} gives the axis step whichever it is. The propagation's loop
     * ({@link #expandRange}) writes this method out in place; this copy serves the repair's re-expansions.
     *
     * @return the number of cells queued
     */
    private int expand(int cell, float value, float ownHalfDensity, int[] potential, float[] halfDensity,
            byte[] costs, int stride) {
        int pushed = 0;
        int east = cell + 1;
        int west = cell - 1;
        int north = cell + stride;
        int south = cell - stride;
        int eastBits = potential[east];
        int westBits = potential[west];
        int northBits = potential[north];
        int southBits = potential[south];
        float northSouthCorner = InterpolatedUpdate.lower(northBits, southBits);
        float eastWestCorner = InterpolatedUpdate.lower(eastBits, westBits);
        if (eastBits >= 0) {
            pushed += relax(east, eastBits, value, northSouthCorner, ownHalfDensity, halfDensity, costs, buckets,
                    bucketShift, currentBucket);
        }
        if (westBits >= 0) {
            pushed += relax(west, westBits, value, northSouthCorner, ownHalfDensity, halfDensity, costs, buckets,
                    bucketShift, currentBucket);
        }
        if (northBits >= 0) {
            pushed += relax(north, northBits, value, eastWestCorner, ownHalfDensity, halfDensity, costs, buckets,
                    bucketShift, currentBucket);
        }
        if (southBits >= 0) {
            pushed += relax(south, southBits, value, eastWestCorner, ownHalfDensity, halfDensity, costs, buckets,
                    bucketShift, currentBucket);
        }
        return pushed;
    }

    /**
     * Updates {@code target} (not final, stored bits {@code targetBits}), an axis neighbour of the just-finalised cell,
     * through the triangles (target, cell, corner) with the lower of its two diagonal corners next to the cell.
     * Written without branches on the data, with integer selections only (C2 compiles them to conditional moves; see
     * {@link InterpolatedUpdate#updateBits} for the float ones): whether the update improves the target is close to a coin toss, and a
     * mispredicted branch costs more than the arithmetic. The lower value is stored whatever happens ({@code min} of
     * the bits: the old value when the update does not improve it), the target is written to the end of its bucket
     * and the bucket's size advanced when it improved. A target lowered again is queued again, also when it stays in
     * its bucket: the entry popped first finalises it and the others are skipped as final (a few percent more
     * entries than cells on the benchmark grids, cheaper than computing the old value's bucket at every update); a
     * cell the focus deferred is checked again with its lower value (and counted in {@link #deferredCount} again if
     * still outside).
     *
     * @return 1 when the target was queued (the caller counts it in {@link #queued}), else 0. Reached cells are recorded for the reset by {@link #propagate} (when popped, and those still
     * queued when it stops), not here.
     */
    private int relax(int target, int targetBits, float value, float corner, float ownHalfDensity,
            float[] halfDensity, byte[] costs, int[] buckets, int shift, int currentBucket) {
        int bestBits = InterpolatedUpdate.updateBits(value, corner, halfDensity[costs[target] & 0xFF] + ownHalfDensity);
        float best = Float.intBitsToFloat(bestBits);
        int queue = bestBits < targetBits ? 1 : 0;
        int bucket = (int) (best * inverseBucketWidth);
        potential[target] = Math.min(targetBits, bestBits);
        int slot = Math.max(bucket, currentBucket) & bucketMask;
        int size = bucketSizes[slot];
        buckets[(slot << shift) + size] = target;
        bucketSizes[slot] = size + queue;
        return queue;
    }

    private void push(int cell, float value) {
        push(cell, value, inverseBucketWidth);
    }

    /** Queues a cell in the bucket of {@code key} (or the current one, if lower) for buckets of 1 / {@code inverseWidth}. */
    private void push(int cell, float key, float inverseWidth) {
        int bucket = (int) (key * inverseWidth);
        if (bucket < currentBucket) {
            bucket = currentBucket;
        }
        int slot = bucket & bucketMask;
        int size = bucketSizes[slot];
        if (size == 1 << bucketShift) {
            growBuckets();
        }
        buckets[(slot << bucketShift) + size] = cell;
        bucketSizes[slot] = size + 1;
        fillBound = Math.max(fillBound, size + 1);
        queued++;
    }

    /**
     * Grows the ring, if needed, so that every bucket has room for {@code pushes} more cells (and the slot
     * {@link #relax} writes without queueing): the hot loop then never checks for room.
     */
    private void makeRoom(int pushes) {
        if (fillBound + pushes < 1 << bucketShift) {
            return;
        }
        int fill = 0;
        for (int size : bucketSizes) {
            fill = Math.max(fill, size);
        }
        fillBound = fill;
        while (fillBound + pushes >= 1 << bucketShift) {
            growBuckets();
        }
    }

    /** Doubles the capacity of every bucket of the ring. */
    private void growBuckets() {
        int[] grown = new int[buckets.length * 2];
        for (int slot = 0; slot < bucketSizes.length; slot++) {
            System.arraycopy(buckets, slot << bucketShift, grown, slot << (bucketShift + 1), bucketSizes[slot]);
        }
        buckets = grown;
        bucketShift++;
    }
}
