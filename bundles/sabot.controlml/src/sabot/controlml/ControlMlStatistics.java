package sabot.controlml;

/**
 * Counters of one connection's ControlML requests since the manager was created (telemetry has its own,
 * {@link TelemetryStatistics}).
 *
 * @param requestsServed     requests this device answered (results and errors)
 * @param errorsAnswered     of those, answered with an error
 * @param duplicatesReplayed sets recognised as retransmissions and answered from the replay cache, not re-applied
 * @param unsolicitedDropped results/errors that matched no request of this client, logged and dropped
 */
public record ControlMlStatistics(long requestsServed, long errorsAnswered, long duplicatesReplayed,
        long unsolicitedDropped) {
}
