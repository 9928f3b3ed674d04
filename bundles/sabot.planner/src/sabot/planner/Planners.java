package sabot.planner;

import java.util.List;
import java.util.Optional;

import sabot.planner.internal.LpnPlanner;
import sabot.planner.internal.ReferencePlanner;

/** Obtains planners by kind or by name; each call returns a new, independent instance. */
public final class Planners {

    /** Names {@link #byName} understands. */
    public static final List<String> NAMES = List.of("lpn", "lpn-bounded", "lpn-incremental", "reference", "dijkstra");

    private Planners() {
    }

    /** @return the LPN navigation-function planner over the whole reachable grid, standard cost model */
    public static Planner lpn() {
        return lpn(CostModel.standard());
    }

    /** @return the LPN navigation-function planner over the whole reachable grid */
    public static Planner lpn(CostModel costModel) {
        return new LpnPlanner(costModel, true);
    }

    /**
     * @return the LPN planner that stops the navigation function once the start's value is final: the same path,
     *         computed over fewer cells when the start is near the goal (for frequent re-planning)
     */
    public static Planner lpnBounded(CostModel costModel) {
        return new LpnPlanner(costModel, false);
    }

    /**
     * @return the LPN planner that, when asked again for the same goals after costs rose locally (a new obstacle),
     *         repairs its navigation function where the change reaches instead of recomputing it (any other change:
     *         full computation). The path equals a fresh computation's up to float rounding.
     */
    public static Planner lpnIncremental(CostModel costModel) {
        return new LpnPlanner(costModel, true, true);
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

    /** @return the planner of that name (see {@link #NAMES}), if any */
    public static Optional<Planner> byName(String name, CostModel costModel) {
        return Optional.ofNullable(switch (name) {
            case "lpn" -> lpn(costModel);
            case "lpn-bounded" -> lpnBounded(costModel);
            case "lpn-incremental" -> lpnIncremental(costModel);
            case "reference" -> reference(costModel);
            case "dijkstra" -> dijkstra(costModel);
            default -> null;
        });
    }
}
