package sabot.fleet;

import java.time.Duration;
import java.util.Map;
import java.util.Objects;

/**
 * A device's figures from the server's archive ({@link ServerStatistics}, docs/STATISTICS.md) over a window ending
 * when the server answered.
 *
 * @param device            its bare JID
 * @param window            the window's length
 * @param sessions          its sessions on the server now (a robot online has one)
 * @param requests          requests to it (gets and sets, at once or stored)
 * @param gets              of those, gets
 * @param sets              of those, sets
 * @param stored            of the sets, commands stored for it as messages (docs/CONTROLML.md section 5)
 * @param answers           its answers (results and errors)
 * @param results           of those, results
 * @param errors            of those, errors
 * @param errorsByCondition the errors by ControlML condition (else the stanza error's; {@code unspecified} without
 *                          one); never null
 * @param answered          requests of the window with an archived answer
 * @param answerP50Ms       median time from a request to its answer at the server, ms; NaN without one
 * @param answerP99Ms       99th percentile of the same (interpolated), ms; NaN without one
 * @param telemetry         telemetry publications it sent
 * @param telemetryAgeS     seconds since its latest publication (in the window or not); NaN without one
 * @param stanzas           every archived row of it (requests, answers, publications)
 * @param stanzasByNode     those by the cluster node that took them; never null
 */
public record ServerFigures(String device, Duration window, int sessions, long requests, long gets, long sets,
        long stored, long answers, long results, long errors, Map<String, Long> errorsByCondition, long answered,
        double answerP50Ms, double answerP99Ms, long telemetry, double telemetryAgeS, long stanzas,
        Map<String, Long> stanzasByNode) {

    /** Checks the fields. */
    public ServerFigures {
        Objects.requireNonNull(device, "device");
        Objects.requireNonNull(window, "window");
        errorsByCondition = Map.copyOf(errorsByCondition);
        stanzasByNode = Map.copyOf(stanzasByNode);
    }

    /** @return telemetry publications per second over the window */
    public double telemetryHz() {
        return telemetry / (window.toMillis() / 1000.0);
    }
}
