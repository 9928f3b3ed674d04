package sabot.xmpp.tests;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;

import sabot.testsupport.xmpp.PrivateXmppServer;

class ProsodySmokeTest extends SmackSmokeTest {

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.prosody();

    @Override
    protected PrivateXmppServer server() {
        return XMPP;
    }

    @Test
    void pepItemReachesASubscribedContact() throws Exception {
        pepItemReachesAContactThatAsksWithNotify();
    }
}
