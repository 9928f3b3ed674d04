/**
 * The fixed-seed benchmark grids of the planner ({@link sabot.tools.grids.BenchmarkGrids}: random, maze and
 * enclosed grids with their start and goal) and the command that writes one as a costmap image for
 * {@code ./sabot plan --costmap} ({@link sabot.tools.grids.GridGenerator}, {@code ./sabot bench planner --grid}).
 * The planner benchmarks (tests/sabot.planner.benchmarks) measure on the same grids.
 */
package sabot.tools.grids;
