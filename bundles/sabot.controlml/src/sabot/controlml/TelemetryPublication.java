package sabot.controlml;

/** A running periodic telemetry publication; see {@link TelemetryManager#publish}. */
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
