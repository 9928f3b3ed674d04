package sabot.planner.internal;

import java.util.Arrays;

import sabot.model.map.CellRegion;

/**
 * The repair of a navigation function after costs rose (a sonar obstacle, a moving obstacle's footprint), instead of a
 * recomputation: the D*-like re-planning step (A. Stentz, "The focussed D* algorithm for real-time replanning", IJCAI
 * 1995) on the values of {@link LpnNavigationFunction}. Its two phases:
 *
 * <ol>
 * <li>{@link #withdraw}: cells are checked in increasing N from the changed ones outwards; a cell whose value its
 * remaining lower neighbours no longer support is withdrawn (marked {@link #RETRACTED}), and only then are its higher
 * neighbours checked. Work is proportional to the cells whose value depended on the change (the "shadow" behind a
 * new obstacle), not to the grid.</li>
 * <li>{@link #seed}: each withdrawn cell gets the value its valid neighbours give it, as a seed in a heap; the
 * navigation function's ordinary propagation takes the seeds into its bucket ring as its front approaches them
 * ({@link #hasSeeds}, {@link #lowestSeed}, {@link #popSeed}) and refills the withdrawn cells. Seeds wait in the heap,
 * sorted, because their values may lie further apart than the ring reaches.</li>
 * </ol>
 *
 * Why a class of its own: the repair is cold code beside the propagation (its own checks, heap and update from stored
 * values); what it shares with the propagation is the value encoding and the interpolated update
 * ({@link InterpolatedUpdate}), so a repaired cell holds what a fresh computation would give it. The
 * propagation's re-expansions of a repaired cell's neighbours stay in its loop ({@code repairing}).
 *
 * <p>Only rises are repaired: a cost that fell can shorten paths anywhere behind it, which this check cannot find;
 * the caller then recomputes.
 */
final class NavigationRepair {

    /**
     * Bits of a cell whose value the repair withdrew: the largest finite float, so that it compares like an unreached
     * cell (any seed or update lowers it) while the propagation refills; those left when it ends were cut off from the
     * goals by the change and become unreached ({@link #forgetCutOff}).
     */
    static final int RETRACTED = 0x7F7FFFFF;
    /** A cell is still supported when its neighbours give at most this factor of its value (float rounding). */
    private static final float SUPPORT_TOLERANCE = 1 + 1e-6f;

    private final float[] density;
    /** Cells keyed by N: checks during {@link #withdraw}, seeds after {@link #seed}. */
    private final CellHeap heap = new CellHeap(256);
    /** The cells the last {@link #withdraw} withdrew, {@link #withdrawnCount} of them. */
    private int[] withdrawn = new int[256];
    private int withdrawnCount;

    /** @param density the cost model's density table, by cell cost */
    NavigationRepair(float[] density) {
        this.density = density;
    }

    /**
     * @return the highest density of a passable cell after the change, at least {@code gridMaxDensity}, or -1 when a
     *         cost in {@code changed} fell (or a cell has no previous cost): not repairable
     */
    float highestDensityAfterRise(PlanningGrid grid, CellRegion changed, float gridMaxDensity) {
        byte[] costs = grid.costs();
        float highest = gridMaxDensity;
        for (int row = changed.minRow(); row <= changed.maxRow(); row++) {
            for (int column = changed.minColumn(); column <= changed.maxColumn(); column++) {
                int before = grid.previousCost(column, row);
                float now = density[costs[grid.index(column, row)] & 0xFF];
                if (before < 0 || now < density[before]) {
                    return -1f;
                }
                if (now > highest && now != Float.POSITIVE_INFINITY) {
                    highest = now;
                }
            }
        }
        return highest;
    }

    /**
     * Withdraws the values the rise in {@code changed} no longer supports (phase 1, see the class comment): each
     * becomes {@link #RETRACTED}, or {@link LpnNavigationFunction#IMPASSABLE} for a cell that became impassable
     * (also in {@code initialPotential}).
     *
     * @return the number of cells withdrawn
     */
    int withdraw(PlanningGrid grid, CellRegion changed, int[] potential, int[] initialPotential) {
        byte[] costs = grid.costs();
        int stride = grid.stride();
        heap.clear();
        for (int row = changed.minRow(); row <= changed.maxRow(); row++) {
            for (int column = changed.minColumn(); column <= changed.maxColumn(); column++) {
                int cell = grid.index(column, row);
                float now = density[costs[cell] & 0xFF];
                if (now == density[grid.previousCost(column, row)]) {
                    continue;
                }
                int bits = potential[cell];
                if (now == Float.POSITIVE_INFINITY) {
                    initialPotential[cell] = LpnNavigationFunction.IMPASSABLE;
                }
                if (bits == LpnNavigationFunction.IMPASSABLE) {
                    continue;
                }
                if (bits == LpnNavigationFunction.UNREACHED) {
                    if (now == Float.POSITIVE_INFINITY) {
                        potential[cell] = LpnNavigationFunction.IMPASSABLE;
                    }
                    continue;
                }
                // the cell itself and its axis neighbours (whose updates use its density) must be checked
                pushCheck(cell, potential);
                pushCheck(cell + 1, potential);
                pushCheck(cell - 1, potential);
                pushCheck(cell + stride, potential);
                pushCheck(cell - stride, potential);
            }
        }
        int count = 0;
        while (!heap.isEmpty()) {
            int cell = heap.pop();
            int bits = potential[cell];
            if (bits >= 0 || bits == LpnNavigationFunction.IMPASSABLE) {
                continue; // already withdrawn, never reached, or impassable
            }
            float value = LpnNavigationFunction.decode(bits);
            boolean nowImpassable = density[costs[cell] & 0xFF] == Float.POSITIVE_INFINITY;
            float supported = nowImpassable ? Float.POSITIVE_INFINITY : recompute(cell, potential, costs, stride);
            if (value == 0f || supported <= value * SUPPORT_TOLERANCE) {
                continue; // goal cells and cells still supported keep their value
            }
            potential[cell] = nowImpassable ? LpnNavigationFunction.IMPASSABLE : RETRACTED;
            if (count == withdrawn.length) {
                withdrawn = Arrays.copyOf(withdrawn, count * 2);
            }
            withdrawn[count++] = cell;
            for (int dy = -stride; dy <= stride; dy += stride) {
                for (int dx = -1; dx <= 1; dx++) {
                    int next = cell + dy + dx;
                    int nextBits = potential[next];
                    if (nextBits < 0 && nextBits != LpnNavigationFunction.IMPASSABLE
                            && LpnNavigationFunction.decode(nextBits) > value) {
                        pushCheck(next, potential);
                    }
                }
            }
        }
        withdrawnCount = count;
        return count;
    }

    /**
     * Queues every withdrawn passable cell that a valid neighbour reaches as a seed, at the value the neighbours give
     * it (phase 2, see the class comment).
     *
     * @return the lowest seed's bucket for buckets of 1 / {@code inverseBucketWidth}, or {@link Integer#MAX_VALUE}
     *         when no withdrawn cell has a valid neighbour
     */
    int seed(PlanningGrid grid, int[] potential, float inverseBucketWidth) {
        byte[] costs = grid.costs();
        int stride = grid.stride();
        int lowestBucket = Integer.MAX_VALUE;
        for (int i = 0; i < withdrawnCount; i++) {
            int cell = withdrawn[i];
            if (potential[cell] == LpnNavigationFunction.IMPASSABLE) {
                continue;
            }
            float seed = recompute(cell, potential, costs, stride);
            if (seed != Float.POSITIVE_INFINITY) {
                lowestBucket = Math.min(lowestBucket, (int) (seed * inverseBucketWidth));
                heap.push(cell, seed);
            }
        }
        return lowestBucket;
    }

    /** Marks the withdrawn cells the propagation did not refill as unreached: the change cut them off from the goals. */
    void forgetCutOff(int[] potential) {
        for (int i = 0; i < withdrawnCount; i++) {
            if (potential[withdrawn[i]] == RETRACTED) {
                potential[withdrawn[i]] = LpnNavigationFunction.UNREACHED;
            }
        }
    }

    /** @return whether seeds wait for the propagation */
    boolean hasSeeds() {
        return !heap.isEmpty();
    }

    /** @return the lowest waiting seed's value (only when {@link #hasSeeds}) */
    float lowestSeed() {
        return heap.lowestKey();
    }

    /** Forgets waiting seeds and checks: a new computation starts. */
    void clear() {
        heap.clear();
    }

    /** N of a cell recomputed from its final neighbours, with the same update as the propagation. */
    private float recompute(int cell, int[] potential, byte[] costs, int stride) {
        float own = density[costs[cell] & 0xFF];
        float best = Float.POSITIVE_INFINITY;
        best = Math.min(best, through(cell + 1, cell + 1 + stride, cell + 1 - stride, own, potential, costs));
        best = Math.min(best, through(cell - 1, cell - 1 + stride, cell - 1 - stride, own, potential, costs));
        best = Math.min(best, through(cell + stride, cell + stride + 1, cell + stride - 1, own, potential, costs));
        best = Math.min(best, through(cell - stride, cell - stride + 1, cell - stride - 1, own, potential, costs));
        return best;
    }

    /** The update of a cell of density {@code own} through its final axis neighbour and that neighbour's corners. */
    private float through(int axis, int corner1, int corner2, float own, int[] potential, byte[] costs) {
        int bits = potential[axis];
        if (bits >= 0 || bits == LpnNavigationFunction.IMPASSABLE) {
            return Float.POSITIVE_INFINITY;
        }
        float value = LpnNavigationFunction.decode(bits);
        float c = 0.5f * (own + density[costs[axis] & 0xFF]);
        float corner = Math.min(finalValue(potential[corner1]), finalValue(potential[corner2]));
        return InterpolatedUpdate.update(value, corner, c);
    }

    private static float finalValue(int bits) {
        return bits < 0 ? LpnNavigationFunction.decode(bits) : Float.POSITIVE_INFINITY;
    }

    /** Adds a final, passable cell to the heap as a check, keyed by its value. */
    private void pushCheck(int cell, int[] potential) {
        int bits = potential[cell];
        if (bits >= 0 || bits == LpnNavigationFunction.IMPASSABLE) {
            return;
        }
        heap.push(cell, LpnNavigationFunction.decode(bits));
    }

    /** @return the lowest waiting seed's cell, removed (only when {@link #hasSeeds}) */
    int popSeed() {
        return heap.pop();
    }
}
