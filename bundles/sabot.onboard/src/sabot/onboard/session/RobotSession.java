package sabot.onboard.session;

import org.jivesoftware.smack.XMPPConnection;
import org.osgi.annotation.versioning.ProviderType;

import sabot.controlml.ControlMlManager;
import sabot.controlml.PresenceLevel;

/**
 * The robot's XMPP connection and its {@link ControlMlManager}. The connection reconnects by itself with back-off;
 * handlers registered on the manager survive reconnections (register them once). Presence and the device's vCard
 * identity are (re)published on every connection.
 */
@ProviderType
public interface RobotSession {

    /** @return the robot's bare JID as configured, e.g. {@code sabot-01@sabot.local} */
    String jid();

    /** @return the connection (may be disconnected; never null once the service is registered) */
    XMPPConnection connection();

    /** @return the ControlML manager of {@link #connection()}; never null */
    ControlMlManager controlMl();

    /** @return true while the connection is authenticated */
    boolean isOnline();

    /**
     * Sets the robot's presence level with a reason (the status text), sent now if online and again after each
     * reconnection.
     */
    void setPresence(PresenceLevel level, String reason);

    /**
     * Adds a listener told when the connection goes online or offline, on the session's notifier thread, in the
     * order the changes happened. A listener added while the session is online is told {@code online()} at once.
     */
    void addListener(SessionListener listener);

    /** Removes a listener added with {@link #addListener}. */
    void removeListener(SessionListener listener);

    /**
     * @return the presence level last set with {@link #setPresence} (what the robot announces while online); never null
     * @since 0.2
     */
    PresenceLevel presenceLevel();

    /**
     * @return the reason last set with {@link #setPresence} (the presence's status text); never null, may be empty
     * @since 0.2
     */
    String presenceReason();

    /**
     * Checks an account's password by logging it in to the robot's XMPP server: the servers, port and TLS trust of this
     * session, SASL as the server offers it (SCRAM-SHA-256 on the lab's servers), no presence sent, the connection
     * closed at once. For a service that lets people log in with their XMPP accounts (the robot's web page); takes a
     * login's time (tens of milliseconds on a LAN), call it off any latency-critical thread.
     *
     * @param account  a bare JID of the robot's own XMPP domain (only its server can check the password)
     * @param password the password; never null
     * @return true when the server accepted the credentials; false when it refused them, or when the account is of
     *         another domain or not a JID
     * @throws java.io.IOException when the server could not be reached or the TLS check failed (the answer is unknown)
     * @since 0.2
     */
    boolean checkPassword(String account, String password) throws java.io.IOException;

    /**
     * The other occupants of the fleet lobby (roster rule 11, docs/CONTROLML.md): the XEP-0045 room that the session
     * joins after each login when one is configured ({@code controlml.lobby}), where the devices and workbenches online
     * meet. An occupant is only a candidate: whether it is one of the lab's robots is the server's word (its shared
     * group in the roster, {@code sabot.fleet.AccessRules.ROBOTS_GROUP}), never its own.
     *
     * @return the occupants' real JIDs (full: account and resource, e.g. {@code sabot-02@sabot.local/onboard}), as the
     *         room shows them, without this session's own; empty without a lobby, while offline, or while the lobby
     *         could not be joined. A snapshot; never null
     * @since 0.3
     */
    java.util.List<String> lobbyMembers();
}
