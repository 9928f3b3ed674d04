package sabot.fleet;

import java.time.Duration;
import java.util.Map;
import java.util.Objects;

import org.jivesoftware.smack.SmackException.NoResponseException;
import org.jivesoftware.smack.SmackException.NotConnectedException;
import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.XMPPException.XMPPErrorException;
import org.jivesoftware.smack.provider.ProviderManager;
import org.jxmpp.jid.EntityBareJid;

import sabot.fleet.internal.StatisticsIq;
import sabot.fleet.internal.StatisticsIqProvider;

/**
 * A device's statistics from the server's archive of every ControlML stanza (docs/STATISTICS.md): an IQ get
 * {@code <statistics xmlns='urn:sabot:archive:1' device='...' seconds='...'/>} to the server's domain, answered by
 * Sabot's ejabberd module for the accounts of the lab's roles (as {@link CommandHistory}), with what
 * {@code ./sabot stats} says of the device over the window: what the clients sent, as the server archived it.
 */
public final class ServerStatistics {

    /** The request's and the answer's element, in {@link CommandHistory#NAMESPACE}. */
    public static final String ELEMENT = "statistics";
    /** The longest window the server accepts (a week); longer ones are refused with {@code bad-request}. */
    public static final Duration MAX_WINDOW = Duration.ofDays(7);

    static {
        ProviderManager.addIQProvider(ELEMENT, CommandHistory.NAMESPACE, new StatisticsIqProvider());
    }

    private ServerStatistics() {
    }

    /**
     * A device's figures over a window ending when the server answered.
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
    public record Figures(String device, Duration window, int sessions, long requests, long gets, long sets,
            long stored, long answers, long results, long errors, Map<String, Long> errorsByCondition, long answered,
            double answerP50Ms, double answerP99Ms, long telemetry, double telemetryAgeS, long stanzas,
            Map<String, Long> stanzasByNode) {

        /** Checks the fields. */
        public Figures {
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

    /**
     * Reads a device's figures.
     *
     * @param connection a connection of an account with a role of the lab
     * @param device     the device's bare JID
     * @param window     1 s..{@link #MAX_WINDOW}, in whole seconds
     * @throws XMPPErrorException    {@code forbidden} without a role of the lab, {@code service-unavailable} where the
     *                               server keeps no archive (Prosody, or ejabberd without {@code --archive sql})
     * @throws IllegalStateException when the server's answer cannot be read (a server of another version)
     */
    public static Figures read(XMPPConnection connection, EntityBareJid device, Duration window)
            throws XMPPErrorException, NoResponseException, NotConnectedException, InterruptedException {
        long seconds = window.toSeconds();
        if (seconds < 1 || window.compareTo(MAX_WINDOW) > 0 || window.toNanosPart() != 0) {
            throw new IllegalArgumentException("window " + window + ": expected whole seconds, 1 s.." + MAX_WINDOW);
        }
        StatisticsIq answer = connection.sendIqRequestAndWaitForResponse(StatisticsIq.request(connection
                .getXMPPServiceDomain(), device, seconds));
        if (answer.problem() != null) {
            throw new IllegalStateException("the server's statistics of " + device + " could not be read: " + answer
                    .problem());
        }
        return answer.figures();
    }
}
