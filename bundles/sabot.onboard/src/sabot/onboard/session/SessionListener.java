package sabot.onboard.session;

import org.osgi.annotation.versioning.ConsumerType;

/** Told when the robot's XMPP session goes online (authenticated) or offline (lost, or closed). */
@ConsumerType
public interface SessionListener {

    /** The connection is authenticated (first login or after a reconnection). */
    void online();

    /** The connection was lost or closed; {@code reason} says why (e.g. the exception's text). */
    void offline(String reason);
}
