package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;

import java.time.Duration;
import java.util.Map;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.StanzaCollector;
import org.jivesoftware.smack.packet.IQ;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smackx.pubsub.GetItemsRequest;
import org.jivesoftware.smackx.pubsub.ItemsExtension;
import org.jivesoftware.smackx.pubsub.PayloadItem;
import org.jivesoftware.smackx.pubsub.PubSubElementType;
import org.jivesoftware.smackx.pubsub.packet.PubSub;
import org.junit.jupiter.api.Tag;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.TestInfo;
import org.junit.jupiter.api.extension.RegisterExtension;

import sabot.controlml.ControlMl;
import sabot.controlml.ControlMlElement;
import sabot.controlml.Resources;
import sabot.controlml.TelemetryManager;
import sabot.testsupport.xmpp.PrivateXmppServer;
import sabot.testsupport.xmpp.Subscriptions;

@Tag("ejabberd")
class EjabberdControlMlTest extends ControlMlOnServerTest {

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.ejabberd();

    @Override
    protected PrivateXmppServer server() {
        return XMPP;
    }

    /**
     * The first values of a new telemetry node in a burst, before the server has answered the first (which carries
     * the publish-options; ejabberd 23.01 refuses them, and the first value is sent again): every value is
     * acknowledged, and the node's item is the last value, not an older one sent again after it. (Prosody takes the
     * options, and keeps no item to ask for: persist_items is false.)
     */
    @Test
    void aBurstOfFirstPublicationsLeavesTheNodeAtTheLastValue(TestInfo info) throws Exception {
        XMPPTCPConnection wb = workbench(info);
        wb.connect().login();
        Robot robot = robot(server().login(unique(info, "robot")), Map.of());
        Subscriptions.mutual(wb, robot.connection(), Duration.ofSeconds(TIMEOUT_S));
        int burst = 20;
        TelemetryManager telemetry = robot.manager().telemetry();
        for (int x = 1; x <= burst; x++) {
            telemetry.publishNow(Resources.POSITION, poseAt(x));
        }
        // the acknowledgements are counted as they arrive, with no event to wait on: asked every 10 ms
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);
        while (telemetry.statistics().published() < burst && System.nanoTime() < deadline) {
            TimeUnit.MILLISECONDS.sleep(10);
        }
        assertEquals(burst, telemetry.statistics().published(), "acknowledged: " + telemetry.statistics());
        assertEquals(0, telemetry.statistics().failed());

        PubSub get = PubSub.createPubsubPacket(robot.jid().asBareJid(), IQ.Type.get, new GetItemsRequest(ControlMl
                .telemetryNode(Resources.POSITION.name()), 1));
        PubSub answer;
        try (StanzaCollector c = wb.createStanzaCollectorAndSend(get)) {
            answer = c.nextResultOrThrow(TimeUnit.SECONDS.toMillis(TIMEOUT_S));
        }
        ItemsExtension items = answer.getExtension(PubSubElementType.ITEMS);
        assertEquals(1, items.getItems().size(), answer.toXML().toString());
        ControlMlElement item = (ControlMlElement) ((PayloadItem<?>) items.getItems()
                .get(0)).getPayload();
        assertEquals(burst, item.value(Resources.POSITION).pose().x(), "the node's item");
    }
}
