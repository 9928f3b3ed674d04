package sabot.controlml;

/**
 * Counters of one connection's ControlML telemetry since its {@link TelemetryManager} was created.
 *
 * @param published items the server accepted
 * @param failed    items that failed or were not sent (not connected)
 * @param received  items received and decoded
 * @param rejected  items received that did not fit their resource's schema
 */
public record TelemetryStatistics(long published, long failed, long received, long rejected) {
}
