package sabot.onboard.remotefs.internal;

import org.junit.jupiter.api.Tag;
import org.junit.jupiter.api.extension.RegisterExtension;

import sabot.testsupport.xmpp.PrivateXmppServer;

/** The remote FS suite on a private ejabberd. */
@Tag("ejabberd")
class RemoteFsOnEjabberdTest extends RemoteFsOnServerTest {

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.ejabberd();

    @Override
    protected PrivateXmppServer server() {
        return XMPP;
    }
}
