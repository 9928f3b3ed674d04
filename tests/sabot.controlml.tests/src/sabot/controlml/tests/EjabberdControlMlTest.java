package sabot.controlml.tests;

import org.junit.jupiter.api.Tag;
import org.junit.jupiter.api.extension.RegisterExtension;

import sabot.testsupport.xmpp.PrivateXmppServer;

@Tag("ejabberd")
class EjabberdControlMlTest extends ControlMlOnServerTest {

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.ejabberd();

    @Override
    protected PrivateXmppServer server() {
        return XMPP;
    }
}
