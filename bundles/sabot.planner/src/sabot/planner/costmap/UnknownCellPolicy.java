package sabot.planner.costmap;

/** What the costmap makes of occupancy-grid cells nothing is known about. */
public enum UnknownCellPolicy {
    /** Unknown is free space (cost 0): optimistic, for maps whose unexplored parts are known to be open. */
    FREE,
    /** Unknown is an obstacle (lethal, and inflated like one). */
    LETHAL,
    /** Unknown stays {@code NO_INFORMATION} (255); the planner's cost model decides whether it may be crossed. */
    KEEP_UNKNOWN
}
