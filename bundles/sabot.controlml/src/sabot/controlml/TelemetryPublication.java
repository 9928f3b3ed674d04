package sabot.controlml;

import org.osgi.annotation.versioning.ProviderType;

/** A running periodic telemetry publication; see {@link TelemetryManager#publish}. */
@ProviderType
public interface TelemetryPublication extends AutoCloseable {

    /** @return the resource published */
    String resource();

    /** @return the publication period in nanoseconds */
    long periodNanos();

    /** Stops publishing; idempotent. */
    void stop();

    @Override
    default void close() {
        stop();
    }
}
