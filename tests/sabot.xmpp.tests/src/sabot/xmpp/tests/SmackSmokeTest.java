package sabot.xmpp.tests;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.lang.reflect.Field;
import java.net.Socket;
import java.time.Duration;
import java.util.concurrent.ArrayBlockingQueue;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.chat2.ChatManager;
import org.jivesoftware.smack.packet.ExtensionElement;
import org.jivesoftware.smack.packet.Message;
import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.packet.XmlEnvironment;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smackx.pep.PepManager;
import org.jivesoftware.smackx.pubsub.PayloadItem;
import org.jivesoftware.smackx.pubsub.PubSubManager;
import org.jivesoftware.smackx.pubsub.SimplePayload;
import org.jivesoftware.smackx.vcardtemp.VCardManager;
import org.jivesoftware.smackx.vcardtemp.packet.VCard;
import org.junit.jupiter.api.Test;

import sabot.testsupport.xmpp.PrivateXmppServer;
import sabot.testsupport.xmpp.Subscriptions;

/**
 * What every later feature relies on, proven with Smack inside OSGi against a real private server: login, chat,
 * vCard, PEP, accounts made by the administrator and stream-management resumption. Subclasses pick the server.
 */
abstract class SmackSmokeTest {

    private static final long TIMEOUT_S = 10;

    protected abstract PrivateXmppServer server();

    /**
     * TLS is required: before STARTTLS the server offers nothing else (no SASL mechanism, so no password can cross in
     * clear); a client that trusts the server's lab CA gets an encrypted session authenticated with SCRAM-SHA-256,
     * one that trusts another CA is refused with one line that says so.
     */
    @Test
    void clientsMustStartTlsAndTrustTheLabCa(@org.junit.jupiter.api.io.TempDir java.nio.file.Path dir)
            throws Exception {
        try (Socket s = new Socket(java.net.InetAddress.getLoopbackAddress(), server().port())) {
            s.setSoTimeout((int) TimeUnit.SECONDS.toMillis(TIMEOUT_S));
            s.getOutputStream().write(("<?xml version='1.0'?><stream:stream to='" + PrivateXmppServer.DOMAIN
                    + "' version='1.0' xmlns='jabber:client' xmlns:stream='http://etherx.jabber.org/streams'>")
                    .getBytes(java.nio.charset.StandardCharsets.UTF_8));
            StringBuilder reply = new StringBuilder();
            byte[] buf = new byte[4096];
            int n;
            while (reply.indexOf("</stream:features>") < 0 && (n = s.getInputStream().read(buf)) > 0) {
                reply.append(new String(buf, 0, n, java.nio.charset.StandardCharsets.UTF_8));
            }
            String features = reply.substring(reply.indexOf("<stream:features>"));
            assertTrue(features.matches("(?s).*<starttls xmlns=.urn:ietf:params:xml:ns:xmpp-tls.>\\s*<required/>.*"),
                    features);
            assertFalse(features.contains("mechanisms"), "SASL offered before TLS: " + features);
        }
        XMPPTCPConnection secured = server().login("tls-user");
        assertTrue(secured.isSecureConnection(), "not encrypted");
        // the accounts are stored as SHA-256 SCRAM keys: SCRAM-SHA-256 (sabot.fleet's, over the ongres library)
        assertEquals("SCRAM-SHA-256", secured.getUsedSaslMechansism());

        java.nio.file.Path other = sabot.testsupport.xmpp.TestCertificates.anotherCa(dir, "another-ca");
        sabot.fleet.ServerTrust stranger = sabot.fleet.ServerTrust.labCa(other);
        XMPPTCPConnection c = new XMPPTCPConnection(PrivateXmppServer.configuration(server().port(), stranger,
                "tls-user", PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD).build());
        Exception refused = assertThrows(Exception.class, c::connect);
        c.instantShutdown();
        String line = stranger.explain(refused, PrivateXmppServer.DOMAIN);
        assertEquals("the certificate for sabot.local is not signed by the CA of " + other + " (SHA-256 "
                + stranger.fingerprints().get(0) + ")", line, () -> "refused as " + refused);
        assertFalse(server().trust().fingerprints().equals(stranger.fingerprints()));
    }

    @Test
    void twoClientsExchangeAChatMessage() throws Exception {
        XMPPTCPConnection alice = server().login("alice-chat");
        XMPPTCPConnection bob = server().login("bob-chat");
        BlockingQueue<Message> received = new ArrayBlockingQueue<>(1);
        ChatManager.getInstanceFor(bob).addIncomingListener((from, message, chat) -> received.offer(message));

        ChatManager.getInstanceFor(alice).chatWith(bob.getUser().asEntityBareJid()).send("hello bob");

        Message m = received.poll(TIMEOUT_S, TimeUnit.SECONDS);
        assertNotNull(m, "bob received nothing");
        assertEquals("hello bob", m.getBody());
        assertEquals(alice.getUser().asEntityBareJid(), m.getFrom().asEntityBareJidIfPossible());
    }

    @Test
    void vcardIsStoredAndFetchedByAnotherClient() throws Exception {
        XMPPTCPConnection robot = server().login("robot-vcard");
        XMPPTCPConnection workbench = server().login("wb-vcard");
        VCard card = new VCard();
        card.setField("DESC", "mobile robot");
        card.setNickName("sabot-01");
        card.setOrganization("Sabot");
        byte[] png = { (byte) 0x89, 'P', 'N', 'G', 13, 10, 26, 10, 1, 2, 3, 4 };
        card.setAvatar(png, "image/png");
        VCardManager.getInstanceFor(robot).saveVCard(card);

        VCard fetched = VCardManager.getInstanceFor(workbench).loadVCard(robot.getUser().asEntityBareJid());

        assertEquals("mobile robot", fetched.getField("DESC"));
        assertEquals("Sabot", fetched.getOrganization());
        assertEquals("sabot-01", fetched.getNickName());
        assertArrayEquals(png, fetched.getAvatar());
        assertEquals("image/png", fetched.getAvatarMimeType());
    }

    @Test
    void pepItemReachesAnExplicitSubscriber() throws Exception {
        String node = "urn:sabot:smoke:pose";
        XMPPTCPConnection robot = server().login("robot-pep-sub");
        XMPPTCPConnection workbench = server().login("wb-pep-sub");
        BlockingQueue<String> events = new ArrayBlockingQueue<>(4);
        PepManager.getInstanceFor(workbench).addPepEventListener(node, SimplePayload.class,
                (from, payload, id, message) -> events.offer(from.asEntityBareJidString() + "|"
                        + ((ExtensionElement) payload).toXML(XmlEnvironment.EMPTY)));
        Subscriptions.mutual(workbench, robot, Duration.ofSeconds(TIMEOUT_S));
        PepManager pep = PepManager.getInstanceFor(robot);
        pep.publish(node, new PayloadItem<>("pose-0", new SimplePayload("<pose xmlns='urn:sabot:smoke'>0 0 0</pose>")));

        // XEP-0060 subscription to the robot's PEP node (its bare JID is the pubsub service)
        PubSubManager.getInstanceFor(workbench, robot.getUser().asEntityBareJid()).getLeafNode(node)
                .subscribe(workbench.getUser());
        events.clear(); // a last-item notification may arrive on subscribing
        pep.publish(node, new PayloadItem<>("pose-1", new SimplePayload("<pose xmlns='urn:sabot:smoke'>1 2 0.5</pose>")));

        String event = events.poll(TIMEOUT_S, TimeUnit.SECONDS);
        while (event != null && !event.contains("1 2 0.5")) {
            event = events.poll(TIMEOUT_S, TimeUnit.SECONDS); // skip a late last-item copy of pose-0
        }
        assertNotNull(event, "no PEP notification for the subscribed node");
        assertTrue(event.startsWith(robot.getUser().asEntityBareJidString() + "|"), event);
    }

    /**
     * PEP's implicit subscription: the workbench has {@code +notify} in its entity caps and a presence subscription.
     * Run on Prosody only: ejabberd 23.01 learns the caps by a disco#info query of its own and, now and then
     * (2 runs in ~12 here), never delivers to that contact although the publishes go on for 10 s; the explicit
     * subscription below is what both servers deliver reliably.
     */
    protected final void pepItemReachesAContactThatAsksWithNotify() throws Exception {
        String node = "urn:sabot:smoke:telemetry";
        XMPPTCPConnection robot = server().login("robot-pep");
        // +notify must be in the subscriber's entity caps before it logs in, so build its connection by hand.
        server().register("wb-pep", PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD);
        XMPPTCPConnection workbench = new XMPPTCPConnection(server().configuration("wb-pep", PrivateXmppServer.DOMAIN,
                PrivateXmppServer.DEFAULT_PASSWORD).build());
        BlockingQueue<String> events = new ArrayBlockingQueue<>(4);
        PepManager.getInstanceFor(workbench).addPepEventListener(node, SimplePayload.class,
                (from, payload, id, message) -> events.offer(from.asEntityBareJidString() + "|"
                        + ((ExtensionElement) payload).toXML(XmlEnvironment.EMPTY)));
        workbench.connect().login();
        try {
            Subscriptions.mutual(workbench, robot, Duration.ofSeconds(TIMEOUT_S));
            // The server learns that the workbench wants notifications (+notify in its entity caps) by a disco#info
            // query of its own, asynchronously after the presence: a publish can overtake it (seen on ejabberd).
            // So publish again, with a new item, until the notification arrives or the time is up. The server takes
            // the caps from a presence of the contact: the one the subscription brought can cross the subscription's
            // own commit and count for nothing (Prosody, once in 15 runs of ./sabot test: no notification in 10 s), so
            // after a publish that brought nothing the workbench announces itself again, as a client does when its
            // state changes.
            String event = null;
            long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);
            for (int i = 1; event == null && System.nanoTime() < deadline; i++) {
                if (i > 1) {
                    workbench.sendStanza(workbench.getStanzaFactory().buildPresenceStanza().ofType(
                            Presence.Type.available).build());
                }
                PepManager.getInstanceFor(robot).publish(node, new PayloadItem<>("pose-" + i,
                        new SimplePayload("<pose xmlns='urn:sabot:smoke'>1 2 0.5</pose>")));
                event = events.poll(500, TimeUnit.MILLISECONDS);
            }
            assertNotNull(event, "no PEP notification");
            assertTrue(event.startsWith(robot.getUser().asEntityBareJidString() + "|"), event);
            assertTrue(event.contains("1 2 0.5"), event);
        } finally {
            workbench.disconnect();
        }
    }

    @Test
    void makingATakenAccountIsRefusedAndTheFirstPasswordHolds() throws Exception {
        server().register("robot-taken", PrivateXmppServer.DOMAIN, "first");
        IOException refused = assertThrows(IOException.class, () -> server().register("robot-taken",
                PrivateXmppServer.DOMAIN, "second"));
        assertTrue(refused.getMessage().contains("robot-taken@sabot.local"), refused.getMessage());
        server().connect(server().configuration("robot-taken", PrivateXmppServer.DOMAIN, "first").build())
                .disconnect();
    }

    @Test
    void connectionsUseTcpNoDelay() throws Exception {
        XMPPTCPConnection alice = server().login("alice-nodelay");
        assertTrue(socketOf(alice).getTcpNoDelay(), "Smack's socket has Nagle on: requests stall ~40 ms");
    }

    @Test
    void streamIsResumedAfterTheSocketDiesAndQueuedMessageArrives() throws Exception {
        XMPPTCPConnection.setUseStreamManagementDefault(true);
        XMPPTCPConnection.setUseStreamManagementResumptionDefault(true);
        XMPPTCPConnection robot = server().login("robot-sm");
        XMPPTCPConnection workbench = server().login("wb-sm");
        assertTrue(robot.isSmEnabled(), "stream management not enabled");
        BlockingQueue<Message> received = new ArrayBlockingQueue<>(4);
        ChatManager.getInstanceFor(robot).addIncomingListener((from, message, chat) -> received.offer(message));

        socketOf(robot).close(); // the network drops: no closing stream element is sent
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);
        while (robot.isConnected() && System.nanoTime() < deadline) {
            Thread.onSpinWait(); // Smack's reader thread notices the closed socket asynchronously
        }
        assertFalse(robot.isConnected());
        assertTrue(robot.isDisconnectedButSmResumptionPossible());

        ChatManager.getInstanceFor(workbench).chatWith(robot.getUser().asEntityBareJid()).send("while you were away");
        robot.connect();
        robot.login();

        assertTrue(robot.streamWasResumed(), "stream was not resumed");
        Message m = received.poll(TIMEOUT_S, TimeUnit.SECONDS);
        assertNotNull(m, "the message sent during the outage was lost");
        assertEquals("while you were away", m.getBody());
    }

    private static Socket socketOf(XMPPTCPConnection connection) throws ReflectiveOperationException {
        Field f = XMPPTCPConnection.class.getDeclaredField("socket");
        f.setAccessible(true);
        return (Socket) f.get(connection);
    }
}
