package sabot.model.geometry;

/**
 * A point in a planar frame (usually the map frame: right-handed, origin at the map's lower-left corner).
 *
 * @param x metres
 * @param y metres
 */
public record Point2D(double x, double y) {

    /** @return the Euclidean distance to {@code other}, in metres */
    public double distanceTo(Point2D other) {
        return Math.hypot(other.x - x, other.y - y);
    }

    /** @return true when both coordinates are finite (neither NaN nor infinite) */
    public boolean isFinite() {
        return Double.isFinite(x) && Double.isFinite(y);
    }
}
