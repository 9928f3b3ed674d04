package sabot.onboard.controlml.internal.peers;

import org.junit.jupiter.api.extension.RegisterExtension;

import sabot.testsupport.xmpp.PrivateXmppServer;

/** {@link PeersOnServerTest} on a private Ejabberd. */
class PeersOnEjabberdTest extends PeersOnServerTest {

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.ejabberd();

    @Override
    protected PrivateXmppServer server() {
        return XMPP;
    }
}
