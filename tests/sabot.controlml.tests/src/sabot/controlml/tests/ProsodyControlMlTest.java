package sabot.controlml.tests;

import org.junit.jupiter.api.extension.RegisterExtension;

import sabot.testsupport.xmpp.PrivateXmppServer;

class ProsodyControlMlTest extends ControlMlOnServerTest {

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.prosody();

    @Override
    protected PrivateXmppServer server() {
        return XMPP;
    }
}
