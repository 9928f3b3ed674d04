package sabot.controlml;

import org.jxmpp.jid.Jid;
import org.osgi.annotation.versioning.ConsumerType;

/**
 * Decides what a requester may do; consulted by the endpoint before any handler runs. Implementations must be
 * thread-safe and fast (called once per request).
 */
@FunctionalInterface
@ConsumerType
public interface AccessPolicy {

    /** Everyone may get and set: for tests and closed labs only. */
    AccessPolicy OPEN = requester -> AccessLevel.SET;
    /** Nobody may do anything: the endpoint's default until a policy is configured. */
    AccessPolicy CLOSED = requester -> AccessLevel.NONE;

    /**
     * @param requester the requester's full JID as the server stamped it (never null)
     * @return its access level; never null
     */
    AccessLevel levelOf(Jid requester);
}
