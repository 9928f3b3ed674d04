package sabot.fleet;

import java.util.List;

import org.jivesoftware.smack.SmackException.NoResponseException;
import org.jivesoftware.smack.SmackException.NotConnectedException;
import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.XMPPException.XMPPErrorException;
import org.jivesoftware.smack.provider.ProviderManager;
import org.jxmpp.jid.EntityBareJid;

import sabot.fleet.internal.HistoryIq;
import sabot.fleet.internal.HistoryIqProvider;

/**
 * A device's command history from the server's archive of every ControlML stanza (docs/ARCHIVE.md): an IQ get
 * {@code <history xmlns='urn:sabot:archive:1' device='...' max='...'/>} to the server's domain, answered by Sabot's
 * ejabberd module for the accounts of the lab's roles. The answer lists the device's commands (sets, sent at once or
 * stored for it), newest first, each with who sent it and its answer.
 */
public final class CommandHistory {

    /** The protocol's namespace. */
    public static final String NAMESPACE = HistoryIq.NAMESPACE;
    /** The request's and the answer's element. */
    public static final String ELEMENT = HistoryIq.ELEMENT;
    /** The most commands one request returns (the server refuses more with {@code bad-request}). */
    public static final int MAX = 500;

    static {
        ProviderManager.addIQProvider(ELEMENT, NAMESPACE, new HistoryIqProvider());
    }

    private CommandHistory() {
    }

    /**
     * Reads a device's latest commands.
     *
     * @param connection a connection of an account with a role of the lab
     * @param device     the device's bare JID
     * @param max        at most this many, 1..{@link #MAX}
     * @return the commands, newest first
     * @throws XMPPErrorException   {@code forbidden} without a role of the lab, {@code service-unavailable} where
     *                               the server keeps no archive (Prosody, or ejabberd without {@code --archive sql})
     * @throws IllegalStateException when the server's answer has commands that cannot be read (a server of another
     *                               version)
     */
    public static List<ArchivedCommand> read(XMPPConnection connection, EntityBareJid device, int max)
            throws XMPPErrorException, NoResponseException, NotConnectedException, InterruptedException {
        return read(connection, device, max, 0);
    }

    /**
     * Reads the commands taken before one of them: the next page of {@link #read(XMPPConnection, EntityBareJid, int)}.
     *
     * @param before the {@link ArchivedCommand#seq()} of the oldest command read so far
     */
    public static List<ArchivedCommand> readBefore(XMPPConnection connection, EntityBareJid device, int max,
            long before) throws XMPPErrorException, NoResponseException, NotConnectedException, InterruptedException {
        if (before < 1) {
            throw new IllegalArgumentException("before " + before + ": expected a command's seq");
        }
        return read(connection, device, max, before);
    }

    private static List<ArchivedCommand> read(XMPPConnection connection, EntityBareJid device, int max, long before)
            throws XMPPErrorException, NoResponseException, NotConnectedException, InterruptedException {
        if (max < 1 || max > MAX) {
            throw new IllegalArgumentException("max " + max + ": expected 1.." + MAX);
        }
        HistoryIq request = HistoryIq.request(connection.getXMPPServiceDomain(), device, max, before);
        HistoryIq answer = connection.sendIqRequestAndWaitForResponse(request);
        if (!answer.problems().isEmpty()) {
            throw new IllegalStateException("the server's command history of " + device + " has commands that could not"
                    + " be read: " + String.join("; ", answer.problems()));
        }
        return answer.commands();
    }
}
