package sabot.model.map;

import sabot.model.geometry.Pose2D;

/**
 * The YAML half of a ROS {@code map_server} map: where the image is and how to read its pixels.
 *
 * @param image          path of the image, relative to the YAML file's folder unless absolute
 * @param resolution     metres per pixel (cell edge), positive
 * @param origin         map-frame pose of the lower-left pixel's lower-left corner; metres, radians (the heading is
 *                       carried but, as in {@code map_server}, not applied)
 * @param negate         true when white means occupied and black free (thresholds keep their meaning)
 * @param occupiedThresh occupancy probability above which a pixel is occupied, in [0, 1]
 * @param freeThresh     occupancy probability below which a pixel is free, in [0, 1], not above {@code occupiedThresh}
 * @param mode           how pixels become occupancy values
 */
public record MapMetadata(String image, double resolution, Pose2D origin, boolean negate, double occupiedThresh,
        double freeThresh, MapMode mode) {

    /** {@code occupied_thresh} that {@code map_saver} writes. */
    public static final double DEFAULT_OCCUPIED_THRESH = 0.65;
    /** {@code free_thresh} that {@code map_saver} writes. */
    public static final double DEFAULT_FREE_THRESH = 0.196;

    /** @throws IllegalArgumentException naming the field when a value is unusable */
    public MapMetadata {
        if (image == null || image.isBlank()) {
            throw new IllegalArgumentException("image must name a file");
        }
        if (!(resolution > 0) || !Double.isFinite(resolution)) {
            throw new IllegalArgumentException("resolution must be a positive number of metres, got " + resolution);
        }
        if (origin == null || !origin.isFinite()) {
            throw new IllegalArgumentException("origin must be a finite pose, got " + origin);
        }
        if (!(occupiedThresh >= 0 && occupiedThresh <= 1)) {
            throw new IllegalArgumentException("occupied_thresh must be in [0, 1], got " + occupiedThresh);
        }
        if (!(freeThresh >= 0 && freeThresh <= 1)) {
            throw new IllegalArgumentException("free_thresh must be in [0, 1], got " + freeThresh);
        }
        if (freeThresh > occupiedThresh) {
            throw new IllegalArgumentException(
                    "free_thresh (" + freeThresh + ") must not exceed occupied_thresh (" + occupiedThresh + ")");
        }
        if (mode == null) {
            throw new IllegalArgumentException("mode must be trinary, scale or raw");
        }
    }

    /** @return metadata as {@code map_saver} writes it: trinary, not negated, default thresholds */
    public static MapMetadata standard(String image, double resolution, Pose2D origin) {
        return new MapMetadata(image, resolution, origin, false, DEFAULT_OCCUPIED_THRESH, DEFAULT_FREE_THRESH,
                MapMode.TRINARY);
    }
}
