/**
 * Path planning on a {@link sabot.model.map.Costmap}: the {@link sabot.planner.Planner} SPI, its results (a
 * {@link sabot.planner.PlanResult} is either a {@link sabot.planner.PlanResult.Found path} or says why the goal is
 * {@link sabot.planner.PlanResult.Unreachable unreachable}; never null), the {@link sabot.planner.CostModel} every
 * planner optimises, and {@link sabot.planner.Planners} to obtain the LPN navigation-function planner or the
 * 8-connected Dijkstra/A* reference.
 *
 * <p>Units: positions in metres in the map frame; costs in the navfn cost unit ({@link CostModel#COST_NEUTRAL} per
 * cell edge of free space).
 */
package sabot.planner;
