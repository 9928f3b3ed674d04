package sabot.workbench.fleet;

import java.util.Map;
import java.util.Objects;

import sabot.controlml.ControlMlCondition;

/**
 * The workbench's own count of its traffic with one robot since the connection was made: an immutable snapshot
 * ({@link FleetState#traffic}). It is what this workbench sent and received, not what the server saw (the server's
 * figures: {@code ./sabot stats}, docs/STATISTICS.md).
 * <p>
 * A <em>stanza</em> is any stanza whose sender (in) or recipient (out) is the robot's bare JID or one of its full JIDs:
 * requests and answers, telemetry notifications (PEP events come from the bare JID), presence. Its <em>bytes</em> are
 * the UTF-8 length of the stanza as Smack serialises it (the wire's bytes before TLS, give or take attribute order and
 * namespace declarations). Rates are per second over the last {@link #RATE_WINDOW_S} complete seconds; round trips
 * are over the last {@link #ROUND_TRIP_WINDOW_S} seconds, in slices of 10 s (the one under way included: between 50
 * and 60 s of answers).
 *
 * @param robot                the robot's bare JID; never null
 * @param stanzasIn            stanzas received from it
 * @param stanzasOut           stanzas sent to it
 * @param bytesIn              bytes received from it
 * @param bytesOut             bytes sent to it
 * @param stanzasInPerSecond   stanzas received per second (Hz)
 * @param stanzasOutPerSecond  stanzas sent per second (Hz)
 * @param bytesInPerSecond     bytes received per second
 * @param bytesOutPerSecond    bytes sent per second
 * @param requests             ControlML requests (get and set) this workbench sent it
 * @param errors               of those, the ones answered with an error, not answered in time or lost with the
 *                             connection, by ControlML condition ({@link ControlMlCondition#TIMEOUT}: no answer in
 *                             time; {@link ControlMlCondition#NOT_CONNECTED}: could not be sent; a plain XMPP error
 *                             without a ControlML condition: {@link ControlMlCondition#UNSPECIFIED}); never null,
 *                             no zero counts
 * @param roundTrips           requests answered (result or error) within the round-trip window
 * @param roundTripP50Ms       median time from sending a request to its answer, ms, over the round-trip window; NaN
 *                             when {@code roundTrips} is 0
 * @param roundTripP99Ms       99th percentile of the same, ms; NaN when {@code roundTrips} is 0
 * @param telemetryItems       telemetry items received from it (every node: position, velocity, mission, obstacles)
 * @param telemetryHz          telemetry items received per second
 * @param telemetryAgeS        seconds since its last telemetry item; NaN before the first
 */
public record TrafficStatistics(String robot, long stanzasIn, long stanzasOut, long bytesIn, long bytesOut,
        double stanzasInPerSecond, double stanzasOutPerSecond, double bytesInPerSecond, double bytesOutPerSecond,
        long requests, Map<ControlMlCondition, Long> errors, long roundTrips, double roundTripP50Ms,
        double roundTripP99Ms, long telemetryItems, double telemetryHz, double telemetryAgeS) {

    /** The rates' window: 10 complete seconds (a rate lags by at most one second, and follows a change within 11 s). */
    public static final int RATE_WINDOW_S = 10;
    /** The round trips' window: the last minute, in slices of 10 s. */
    public static final int ROUND_TRIP_WINDOW_S = 60;

    public TrafficStatistics {
        Objects.requireNonNull(robot, "robot");
        errors = Map.copyOf(errors);
    }

    /** @return every error counted, whatever its condition */
    public long errorCount() {
        return errors.values().stream().mapToLong(Long::longValue).sum();
    }
}
