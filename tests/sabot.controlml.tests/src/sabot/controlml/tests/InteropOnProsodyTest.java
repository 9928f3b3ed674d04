package sabot.controlml.tests;

import org.junit.jupiter.api.extension.RegisterExtension;

import sabot.testsupport.xmpp.PrivateXmppServer;

/** The slixmpp interop suite against the device on a private Prosody. */
class InteropOnProsodyTest extends InteropSuiteTest {

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.prosody();

    @Override
    protected PrivateXmppServer server() {
        return XMPP;
    }
}
