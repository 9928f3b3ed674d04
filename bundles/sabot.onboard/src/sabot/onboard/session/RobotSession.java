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
}
