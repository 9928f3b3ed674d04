package sabot.identity.tests;

import org.junit.jupiter.api.extension.RegisterExtension;

import sabot.testsupport.xmpp.PrivateXmppServer;

class ProsodyIdentityTest extends IdentityOnServerTest {

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.prosody();

    @Override
    protected PrivateXmppServer server() {
        return XMPP;
    }
}
