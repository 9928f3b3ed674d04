package sabot.onboard.controlml.internal.peers;

import org.junit.jupiter.api.extension.RegisterExtension;

import sabot.testsupport.xmpp.PrivateXmppServer;

/** {@link PeersOnServerTest} on a private Prosody. */
class PeersOnProsodyTest extends PeersOnServerTest {

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.prosody();

    @Override
    protected PrivateXmppServer server() {
        return XMPP;
    }
}
