package sabot.planner;

/** Why a planner found no path; every reason is a property of the request or the map, not of the planner. */
public enum UnreachableReason {
    /** The start is NaN/infinite, or the goal set is empty or holds a NaN/infinite point. */
    INVALID_REQUEST,
    /** The start lies outside the costmap. */
    START_OUTSIDE_MAP,
    /** A goal lies outside the costmap. */
    GOAL_OUTSIDE_MAP,
    /** The start cell is lethal, inscribed, or unknown where unknown is impassable. */
    START_IN_OBSTACLE,
    /** A goal cell is lethal, inscribed, or unknown where unknown is impassable. */
    GOAL_IN_OBSTACLE,
    /** Start and goal are both free, but no free path joins them: the goal's free region does not hold the start. */
    GOAL_ENCLOSED
}
