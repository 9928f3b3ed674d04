package sabot.localization;

/**
 * A ceiling landmark whose map position is known.
 *
 * @param id identifier (e.g. the marker's code)
 * @param x  metres, map frame
 * @param y  metres, map frame
 */
public record Landmark(String id, double x, double y) {

    public Landmark {
        if (!Double.isFinite(x) || !Double.isFinite(y)) {
            throw new IllegalArgumentException("landmark position must be finite");
        }
    }
}
