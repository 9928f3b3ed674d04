package sabot.modbus;

import java.time.Duration;

/**
 * The power board's configuration (file 2).
 *
 * @param designCapacity capacity of the full battery, Ah (1 mAh resolution; read-only on the board)
 * @param period         time between measurements (map bounds 20–1000 ms, 1 ms resolution); never null
 */
public record PowerConfig(double designCapacity, Duration period) {
}
