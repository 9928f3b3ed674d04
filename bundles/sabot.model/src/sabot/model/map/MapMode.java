package sabot.model.map;

import java.util.Locale;
import java.util.Optional;

/**
 * How {@code map_server} turns pixel values into occupancy (its YAML key {@code mode}; source: ROS
 * {@code map_server/src/image_loader.cpp}).
 */
public enum MapMode {
    /** Occupied (100), free (0) or unknown (-1), decided by the two thresholds. The default. */
    TRINARY,
    /** Like trinary, but values between the thresholds become a graded occupancy {@code 99 * ratio}. */
    SCALE,
    /** The pixel value is the cell value (after {@code negate}); 0..100 kept, anything above 100 is unknown. */
    RAW;

    /** @return the name used in the YAML file */
    public String yamlName() {
        return name().toLowerCase(Locale.ROOT);
    }

    /** @return the mode with that YAML name, if any */
    public static Optional<MapMode> fromYamlName(String name) {
        for (MapMode mode : values()) {
            if (mode.yamlName().equals(name)) {
                return Optional.of(mode);
            }
        }
        return Optional.empty();
    }
}
