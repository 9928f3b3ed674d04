package sabot.fleet.tests;

import org.junit.jupiter.api.Tag;
import org.junit.jupiter.api.extension.RegisterExtension;

import sabot.testsupport.xmpp.PrivateXmppServer;

@Tag("ejabberd")
class EjabberdFleetTest extends FleetOnServerTest {

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.ejabberd();

    @Override
    protected PrivateXmppServer server() {
        return XMPP;
    }
}
