package sabot.model.map;

/**
 * The integer address of one grid cell.
 *
 * @param column 0-based, along the map's +x axis
 * @param row    0-based, along the map's +y axis (row 0 is the bottom row of the map, the last row of an image)
 */
public record Cell(int column, int row) {
}
