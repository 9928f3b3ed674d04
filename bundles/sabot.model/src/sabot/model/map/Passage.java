package sabot.model.map;

/**
 * A narrow passage of a map (a door's opening, a corridor) through which robots pass one at a time
 * (docs/PASSAGES.md): the rectangle of its narrow part, metres in the map frame, from the map's
 * {@value MapServerFormat#PASSAGES_KEY}. Immutable.
 *
 * @param id   its number on the map, from 1 in the YAML's order: how robots name it to each other
 * @param minX west edge, m
 * @param minY south edge, m
 * @param maxX east edge, m, above minX
 * @param maxY north edge, m, above minY
 */
public record Passage(int id, double minX, double minY, double maxX, double maxY) {

    /** @throws IllegalArgumentException when the id is below 1 or the rectangle is empty or not finite */
    public Passage {
        if (id < 1) {
            throw new IllegalArgumentException("passage id must be >= 1, got " + id);
        }
        if (!Double.isFinite(minX) || !Double.isFinite(minY) || !Double.isFinite(maxX) || !Double.isFinite(maxY)
                || !(maxX > minX) || !(maxY > minY)) {
            throw new IllegalArgumentException("passage " + id + " is not a rectangle: [" + minX + ", " + minY + ", "
                    + maxX + ", " + maxY + "]");
        }
    }

    /** @return the distance from (x, y) to the rectangle, m (0 inside it) */
    public double distance(double x, double y) {
        double dx = Math.max(0, Math.max(minX - x, x - maxX));
        double dy = Math.max(0, Math.max(minY - y, y - maxY));
        return Math.hypot(dx, dy);
    }

    /** @return whether a disc of {@code radius} centred on (x, y) overlaps the rectangle */
    public boolean touches(double x, double y, double radius) {
        return distance(x, y) < radius;
    }
}
