package sabot.controlml.payload;

/**
 * A detected obstacle approximated by a disc in the map frame.
 *
 * @param x      metres
 * @param y      metres
 * @param radius metres, &ge; 0
 */
public record Obstacle(double x, double y, double radius) {
}
