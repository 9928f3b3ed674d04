package sabot.planner;

import java.util.List;
import java.util.Optional;

import sabot.planner.internal.LpnPlanner;
import sabot.planner.internal.ReferencePlanner;

/** Obtains planners by kind or by name; each call returns a new, independent instance. */
public final class Planners {

    /** Names {@link #byName} understands. */
    public static final List<String> NAMES = List.of("lpn", "lpn-bounded", "lpn-focused", "lpn-incremental", "reference",
            "dijkstra");

    private Planners() {
    }

    /** @return the LPN navigation-function planner over the whole reachable grid, standard cost model */
    public static Planner lpn() {
        return lpn(CostModel.standard());
    }

    /** @return the LPN navigation-function planner over the whole reachable grid */
    public static Planner lpn(CostModel costModel) {
        return lpn(costModel, 1);
    }

    /**
     * @param threads 1 or 2; both compute on the calling thread (a helper thread would have to meet the propagation
     *                at every bucket hand-over, and stalls whenever another process holds the CPU); 2 is accepted so
     *                that configurations asking for it keep working
     * @return the LPN navigation-function planner over the whole reachable grid
     */
    public static Planner lpn(CostModel costModel, int threads) {
        return new LpnPlanner(costModel, true, false, threads);
    }

    /**
     * @return the LPN planner that stops the navigation function once the start's value is final: the same path,
     *         computed over fewer cells when the start is near the goal (for frequent re-planning)
     */
    public static Planner lpnBounded(CostModel costModel) {
        return new LpnPlanner(costModel, false);
    }

    /**
     * @return the LPN planner that computes the navigation function in the order of N, as {@link #lpnBounded}, but
     *         expands only cells whose N plus a lower bound of the cost to the start (c_min times the straight
     *         distance, as A*'s heuristic) stays within a bound of the start's value, raised and recomputed when the
     *         start is not reached within it: the path of {@link #lpn} (to the order effects of bucketed expansion),
     *         computed over far fewer cells when the path is not much longer than the straight line (random
     *         1000 x 1000: 338 k of 736 k cells), a little slower than {@link #lpnBounded} when it is (a maze); as
     *         complete (an enclosed goal or start is reported as such)
     */
    public static Planner lpnFocused(CostModel costModel) {
        return LpnPlanner.focused(costModel);
    }

    /**
     * @return the LPN planner that, when asked again for the same goals after costs rose locally (a new obstacle),
     *         repairs its navigation function where the change reaches instead of recomputing it (any other change:
     *         full computation). The path equals a fresh computation's up to float rounding.
     */
    public static Planner lpnIncremental(CostModel costModel) {
        return lpnIncremental(costModel, 1);
    }

    /** @return {@link #lpnIncremental(CostModel)}; {@code threads} 1 or 2, both on the calling thread (see {@link #lpn(CostModel, int)}) */
    public static Planner lpnIncremental(CostModel costModel, int threads) {
        return new LpnPlanner(costModel, true, true, threads);
    }

    /** @return the 8-connected A* reference, standard cost model */
    public static Planner reference() {
        return reference(CostModel.standard());
    }

    /** @return the 8-connected A* reference */
    public static Planner reference(CostModel costModel) {
        return new ReferencePlanner(costModel, true);
    }

    /** @return the 8-connected Dijkstra reference (settles every cell cheaper than the start) */
    public static Planner dijkstra(CostModel costModel) {
        return new ReferencePlanner(costModel, false);
    }

    /** @return the planner of that name (see {@link #NAMES}), if any, on one thread */
    public static Optional<Planner> byName(String name, CostModel costModel) {
        return byName(name, costModel, 1);
    }

    /**
     * @param threads 1 or 2 (both compute on the calling thread, see {@link #lpn(CostModel, int)})
     * @return the planner of that name (see {@link #NAMES}), if any
     */
    public static Optional<Planner> byName(String name, CostModel costModel, int threads) {
        if (threads < 1 || threads > 2) {
            throw new IllegalArgumentException("threads must be 1 or 2, not " + threads);
        }
        return Optional.ofNullable(switch (name) {
            case "lpn" -> lpn(costModel, threads);
            case "lpn-bounded" -> lpnBounded(costModel);
            case "lpn-focused" -> lpnFocused(costModel);
            case "lpn-incremental" -> lpnIncremental(costModel, threads);
            case "reference" -> reference(costModel);
            case "dijkstra" -> dijkstra(costModel);
            default -> null;
        });
    }
}
