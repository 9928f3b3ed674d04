package sabot.planner.internal;

import java.util.Arrays;

/**
 * The landmark lower bound ("ALT": A. V. Goldberg, C. Harrelson, "Computing the shortest path: A* search meets graph
 * theory", SODA 2005) that focuses {@link LpnNavigationFunction#computeFocused} on grids where the straight line
 * bounds poorly. N is computed from each of {@link #LANDMARKS} cells over the whole grid; by the triangle inequality
 * the cost between a cell p and the start is at least {@code |N_l(p) - N_l(start)|} for every landmark l: a bound that
 * follows the corridors of a maze, where the straight line cuts through walls and excludes nothing.
 *
 * <p>Why a class of its own: building and choosing landmarks is cold code (a few whole-grid computations per map, a
 * choice per plan), kept apart from the propagation; only {@link #bound} is read per cell, by the focus test of the
 * propagation's hot loop, and it is a small final method that C2 inlines there.
 *
 * <p>Life cycle: landmarks are wanted once focused plans needed a large excess over the straight line
 * ({@link #noteStraightLineExcess}), built at the start of the next focused computation ({@link #build}), used by
 * every focused computation while costs only rise (a rise makes paths dearer, so the bound stays valid), and dropped
 * when a cost falls or the grid is replaced ({@link #drop}). A set that served fewer than
 * {@value #PAYBACK_PLANS} plans doubles the number of poorly bounded plans awaited before the next build, so that a
 * map whose costs keep falling does not pay for landmarks at every other plan.
 */
final class LandmarkBound {

    /**
     * Landmarks, chosen farthest first: on the benchmark maze two already bound the start's cost within 0.01 %, on
     * random-1000 four within 0.02 %.
     */
    static final int LANDMARKS = 4;
    /**
     * A focused computation whose straight-line bound needed at least this excess (a path more than twice the
     * straight line: a maze) counts as poorly bounded.
     */
    static final float WANTED_EXCESS = 1f;
    /**
     * First excess of the focus over the landmarks' lower bound of the start's cost: 0.1 %. On the benchmark maze
     * the landmarks bound the start's cost within 0.001 %; a larger first excess only widens the region expanded.
     */
    static final float FIRST_EXCESS = 0.001f;
    /**
     * The bound is scaled down by this fraction: the interpolated values satisfy the triangle inequality it rests on
     * only nearly (float rounding and the interpolation's dependence on the direction of propagation: within
     * 0.004 % of the path's cost on the benchmark grids); the focus's margin of four diagonal steps covers the rest.
     * A bound that is too high in places costs at most a slightly dearer path, never a missed one.
     */
    private static final float SLACK = 0.001f;
    /** {@code 1 - SLACK}, the factor of every bound. */
    private static final float SCALE = 1 - SLACK;
    /** Plans a set of landmarks must serve to pay for its building (five computations over the whole grid). */
    private static final int PAYBACK_PLANS = 8;
    /** Most poorly bounded plans awaited before landmarks are built again after a set that did not pay back. */
    private static final int MAX_PATIENCE = 64;

    /** N from each landmark by padded index (+infinity where unreached, NaN for a landmark a small region lacks), or null. */
    private float[][] values;
    /** Largest finite N of each landmark: its bound never exceeds it. */
    private final float[] reach = new float[LANDMARKS];
    /**
     * The two landmarks the running computation bounds with (the two tightest at the goal, as Goldberg and Werneck's
     * "active landmarks": two arrays read per cell instead of four) and their N at the start.
     */
    private float[] active;
    private float[] otherActive;
    private float activeAtStart;
    private float otherActiveAtStart;
    /** The larger {@link #reach} of the two active landmarks: no {@link #bound} exceeds it. */
    private float activeReach;
    /** Poorly bounded plans since the landmarks were last dropped, the number that triggers a build, plans served. */
    private int poorlyBoundedPlans;
    private int patience = 1;
    private int plans;

    /** @return whether landmarks are built (focused computations then bound with them) */
    boolean isBuilt() {
        return values != null;
    }

    /** @return whether enough poorly bounded plans asked for landmarks that are not built yet */
    boolean isDue() {
        return values == null && poorlyBoundedPlans >= patience;
    }

    /**
     * @return whether a fall of a cost matters: landmarks are built (their bounds may then exceed the new costs) or
     *         poorly bounded plans are being counted towards a build
     */
    boolean watchesCostFalls() {
        return values != null || poorlyBoundedPlans > 0;
    }

    /** Counts a focused plan bounded by the straight line that needed {@code excess}: poorly bounded if large. */
    void noteStraightLineExcess(float excess) {
        if (excess >= WANTED_EXCESS) {
            poorlyBoundedPlans++;
        }
    }

    /**
     * Computes N from {@link #LANDMARKS} cells over the whole grid with {@code function} (overwriting its values),
     * each the reached cell farthest from the ones before (the first: farthest from {@code seed}), and keeps the
     * values. Farthest landmarks lie "behind" most starts and goals, where their bounds are tight (Goldberg and
     * Harrelson).
     */
    void build(LpnNavigationFunction function, int seed) {
        int cells = function.potential().length;
        float[][] built = new float[LANDMARKS][cells];
        float[] nearest = new float[cells];
        Arrays.fill(nearest, Float.POSITIVE_INFINITY);
        function.compute(new int[] {seed}, -1);
        int next = farthest(function.potential(), null);
        int count = 0;
        for (; count < LANDMARKS && next >= 0; count++) {
            function.compute(new int[] {next}, -1);
            int[] potential = function.potential();
            float[] landmark = built[count];
            float farthestValue = 0f;
            for (int i = 0; i < cells; i++) {
                float value = LpnNavigationFunction.decode(potential[i]);
                landmark[i] = value;
                if (value < nearest[i]) {
                    nearest[i] = value;
                }
                if (value != Float.POSITIVE_INFINITY && value > farthestValue) {
                    farthestValue = value;
                }
            }
            reach[count] = farthestValue;
            next = farthest(potential, nearest);
        }
        // a region too small for all landmarks (every cell already one): the missing ones are never chosen (NaN)
        for (int l = count; l < LANDMARKS; l++) {
            Arrays.fill(built[l], Float.NaN);
        }
        values = built;
        plans = 0;
    }

    /**
     * @return the reached cell of {@code potential} whose value in {@code nearest} (null: its own value) is largest
     *         and finite, or -1 when there is none above 0
     */
    private static int farthest(int[] potential, float[] nearest) {
        int best = -1;
        float bestValue = 0f;
        for (int i = 0; i < potential.length; i++) {
            int bits = potential[i];
            if (bits < 0 && bits != LpnNavigationFunction.IMPASSABLE) {
                float value = nearest == null ? LpnNavigationFunction.decode(bits) : nearest[i];
                if (value > bestValue) {
                    bestValue = value;
                    best = i;
                }
            }
        }
        return best;
    }

    /**
     * Activates, for a plan from {@code startCell} to {@code goals}, the two landmarks whose bounds at the goals are
     * highest (among those the start is connected to), and counts the plan as served by this set.
     *
     * @return false when no landmarks are built or the start is connected to none
     */
    boolean activate(int[] goals, int startCell) {
        if (values == null) {
            return false;
        }
        int best = -1;
        int second = -1;
        float bestBound = -1f;
        float secondBound = -1f;
        for (int l = 0; l < LANDMARKS; l++) {
            float atStart = values[l][startCell];
            if (!(atStart < Float.POSITIVE_INFINITY)) {
                continue; // not connected, or a missing landmark (NaN)
            }
            float bound = Float.POSITIVE_INFINITY;
            for (int goal : goals) {
                bound = Math.min(bound, Math.abs(values[l][goal] - atStart));
            }
            if (bound > bestBound) {
                second = best;
                secondBound = bestBound;
                best = l;
                bestBound = bound;
            } else if (bound > secondBound) {
                second = l;
                secondBound = bound;
            }
        }
        if (best < 0) {
            return false;
        }
        second = second < 0 ? best : second;
        active = values[best];
        activeAtStart = active[startCell];
        otherActive = values[second];
        otherActiveAtStart = otherActive[startCell];
        activeReach = Math.max(reach[best], reach[second]);
        plans++;
        return true;
    }

    /**
     * @return the active landmarks' lower bound of the cost between {@code cell} and the start (+infinity: not
     *         connected to the start); read per cell by the focus test
     */
    float bound(int cell) {
        float gap = Math.abs(active[cell] - activeAtStart);
        float otherGap = Math.abs(otherActive[cell] - otherActiveAtStart);
        // the larger gap as the integer maximum of the bits (both are non-negative): C2 compiles a float selection
        // to a compare and a jump, and which gap is larger is a coin toss
        return SCALE * Float.intBitsToFloat(Math.max(Float.floatToRawIntBits(gap), Float.floatToRawIntBits(otherGap)));
    }

    /** @return the least {@link #bound} at the goals (+infinity: no goal is connected to the start) */
    float nearestGoalBound(int[] goals) {
        float nearest = Float.POSITIVE_INFINITY;
        for (int goal : goals) {
            nearest = Math.min(nearest, bound(goal));
        }
        return nearest;
    }

    /** @return the highest value {@link #bound} can take for the active landmarks */
    float boundReach() {
        return SCALE * activeReach;
    }

    /** Forgets the landmarks after a cost fell or the grid was replaced; a set that served few plans is rebuilt later. */
    void drop() {
        if (values != null) {
            patience = plans >= PAYBACK_PLANS ? 1 : Math.min(2 * patience, MAX_PATIENCE);
        }
        values = null;
        poorlyBoundedPlans = 0;
    }
}
