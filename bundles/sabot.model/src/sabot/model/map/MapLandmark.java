package sabot.model.map;

/**
 * A passive marker on the ceiling above a point of the map, as a ceiling-landmark camera (the robot's landmark board)
 * identifies it. Maps list their markers in a landmarks file named by the YAML key {@code sabot_landmarks} (see
 * {@link MapServerFormat#readLandmarks}).
 *
 * @param id the marker's code, 1–65535 (0 is the board's "none seen")
 * @param x  map-frame x of the point below the marker, m
 * @param y  map-frame y of that point, m
 */
public record MapLandmark(int id, double x, double y) {

    /** The smallest marker id; 0 means "no marker" on the bus. */
    public static final int MIN_ID = 1;
    /** The largest marker id: the board reports it in one 16-bit register. */
    public static final int MAX_ID = 65535;

    /** @throws IllegalArgumentException naming the field when the id is out of range or a coordinate not finite */
    public MapLandmark {
        if (id < MIN_ID || id > MAX_ID) {
            throw new IllegalArgumentException("landmark id must be in " + MIN_ID + ".." + MAX_ID + ", got " + id);
        }
        if (!Double.isFinite(x) || !Double.isFinite(y)) {
            throw new IllegalArgumentException("landmark " + id + " position must be finite, got (" + x + ", " + y
                    + ")");
        }
    }
}
