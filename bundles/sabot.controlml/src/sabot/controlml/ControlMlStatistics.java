package sabot.controlml;

/**
 * Counters of one connection's ControlML traffic since the manager was created.
 *
 * @param requestsServed     requests this device answered (results and errors)
 * @param errorsAnswered     of those, answered with an error
 * @param duplicatesReplayed sets recognised as retransmissions and answered from the replay cache, not re-applied
 * @param unsolicitedDropped results/errors that matched no request of this client, logged and dropped
 * @param telemetryPublished telemetry items the server accepted
 * @param telemetryFailed    telemetry items that failed or were not sent (not connected)
 * @param telemetryReceived  telemetry items received and decoded
 * @param telemetryRejected  telemetry items received that did not fit their resource's schema
 */
public record ControlMlStatistics(long requestsServed, long errorsAnswered, long duplicatesReplayed,
        long unsolicitedDropped, long telemetryPublished, long telemetryFailed, long telemetryReceived,
        long telemetryRejected) {
}
