package sabot.modbus;

import java.time.Duration;

/**
 * The ceiling-landmark board's configuration (file 2).
 *
 * @param viewRadius markers farther than this horizontally from the camera are not reported, m (map bounds 0.1–5 m,
 *                   1 mm resolution)
 * @param period     time between measurements (map bounds 20–1000 ms, 1 ms resolution); never null
 */
public record LandmarkConfig(double viewRadius, Duration period) {
}
