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

    /** Everyone is a maintainer: for tests of the protocol itself only (a robot never runs with it by default). */
    AccessPolicy OPEN = requester -> Role.MAINTAINER;
    /** Nobody may do anything: the endpoint's default until a policy is configured. */
    AccessPolicy CLOSED = requester -> Role.NONE;

    /**
     * @param requester the requester's full JID as the server stamped it (never null)
     * @return its role on this device; never null
     */
    Role roleOf(Jid requester);
}
