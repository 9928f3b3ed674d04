/**
 * Building the costmap a planner reads: obstacles from an occupancy grid or from sensors, inflated by the robot's
 * inscribed radius with a decaying cost beyond ({@link sabot.planner.costmap.InflationParameters}), a policy for
 * unknown cells, and the cost of the space moving obstacles are about to sweep
 * ({@link sabot.planner.costmap.MovingObstacleModel}). {@link sabot.planner.costmap.CostmapLayers} keeps them and
 * updates only the cells a change can affect. Distances in metres, speeds in metres per second, times in seconds.
 */
package sabot.planner.costmap;
