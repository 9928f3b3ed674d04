package sabot.onboard.remotefs.internal;

import org.junit.jupiter.api.extension.RegisterExtension;

import sabot.testsupport.xmpp.PrivateXmppServer;

/** The remote FS suite on a private Prosody. */
class RemoteFsOnProsodyTest extends RemoteFsOnServerTest {

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.prosody();

    @Override
    protected PrivateXmppServer server() {
        return XMPP;
    }
}
