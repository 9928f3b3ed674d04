package sabot.controlml;

import org.osgi.annotation.versioning.ProviderType;

/** A running periodic telemetry publication; see {@link TelemetryManager#publish}. */
@ProviderType
public interface TelemetryPublication extends AutoCloseable {

    /** @return the resource published */
    String resource();

    /** @return the publication period in nanoseconds now (0 while the rate is 0) */
    long periodNanos();

    /** @return publications per second now */
    double rate();

    /**
     * Changes the rate. The next publication comes one new period after the last one (at once when that time has
     * passed), so a faster rate shows at once and a slower one never leaves a gap longer than its period.
     *
     * @param rateHz publications per second, 0 (publish nothing until the rate changes) to 1000
     */
    void setRate(double rateHz);

    /** Stops publishing; idempotent. */
    void stop();

    @Override
    default void close() {
        stop();
    }
}
