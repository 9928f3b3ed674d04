package sabot.fleet;

import java.time.Duration;

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
    public static final String ELEMENT = StatisticsIq.ELEMENT;
    /** The longest window the server accepts (a week); longer ones are refused with {@code bad-request}. */
    public static final Duration MAX_WINDOW = Duration.ofDays(7);

    static {
        ProviderManager.addIQProvider(ELEMENT, CommandHistory.NAMESPACE, new StatisticsIqProvider());
    }

    private ServerStatistics() {
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
    public static ServerFigures read(XMPPConnection connection, EntityBareJid device, Duration window)
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
