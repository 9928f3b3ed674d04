/**
 * Maps of the robot's world: the {@link sabot.model.map.OccupancyGrid} (what the sensors or a saved map say),
 * the {@link sabot.model.map.Costmap} the planners read (ROS {@code costmap_2d} value convention), and the ROS
 * {@code map_server} file format (PGM image + YAML description) in {@link sabot.model.map.MapServerFormat}.
 *
 * <p>Every grid is laid out in the map frame: right-handed, cell (0, 0) at the lower-left corner, column index
 * along +x, row index along +y; a cell covers {@code resolution} metres on a side. Image files store the top row
 * first, so the file format flips rows when reading and writing.
 */
package sabot.model.map;
