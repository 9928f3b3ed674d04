package sabot.controlml.tests;

import org.junit.jupiter.api.Tag;
import org.junit.jupiter.api.extension.RegisterExtension;

import sabot.testsupport.xmpp.PrivateXmppServer;

/** The slixmpp interop suite against the device on a private Ejabberd. */
@Tag("ejabberd")
class InteropOnEjabberdTest extends InteropSuiteTest {

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.ejabberd();

    @Override
    protected PrivateXmppServer server() {
        return XMPP;
    }
}
