package sabot.identity.tests;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;

import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smackx.vcardtemp.VCardManager;
import org.jivesoftware.smackx.vcardtemp.packet.VCard;
import org.junit.jupiter.api.Test;
import org.osgi.framework.Bundle;
import org.osgi.framework.FrameworkUtil;
import org.osgi.util.tracker.ServiceTracker;

import sabot.identity.DeviceCard;
import sabot.identity.DeviceIdentityManager;
import sabot.identity.DeviceProfile;
import sabot.identity.IdentityResult;
import sabot.identity.Inventory;
import sabot.identity.InventorySource;
import sabot.identity.QrInventory;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * A robot publishes its vCard with the QR code of its real inventory; another client fetches it from the server
 * and decodes the QR code to the identical inventory. Subclasses pick the server.
 */
abstract class IdentityOnServerTest {

    protected abstract PrivateXmppServer server();

    private static Inventory runningInventory() throws Exception {
        Bundle identity = FrameworkUtil.getBundle(InventorySource.class);
        identity.start(Bundle.START_ACTIVATION_POLICY);
        ServiceTracker<InventorySource, InventorySource> t = new ServiceTracker<>(identity.getBundleContext(),
                InventorySource.class, null);
        t.open();
        try {
            return t.waitForService(10_000).inventory(Fixtures.hardware(Fixtures.SERIAL));
        } finally {
            t.close();
        }
    }

    @Test
    void anotherClientFetchesTheVCardAndDecodesTheQrToTheIdenticalInventory() throws Exception {
        XMPPTCPConnection robot = server().login("robot-id");
        XMPPTCPConnection workbench = server().login("wb-id");
        Inventory inventory = runningInventory();
        DeviceProfile profile = Fixtures.profile(robot.getUser().asBareJid().toString());

        QrInventory.Encoded published = DeviceIdentityManager.getInstanceFor(robot).publish(profile, inventory)
                .orElseThrow();
        DeviceCard card = DeviceIdentityManager.getInstanceFor(workbench).fetch(robot.getUser().asEntityBareJid())
                .orElseThrow();

        assertEquals(profile, card.profile());
        assertNull(card.inventoryProblem());
        assertEquals(inventory, card.inventory());
        assertEquals("45.764043", DeviceProfile.geo(card.profile().latitude()), "GEO to six decimals");
        // Smack's own vCard API on the reading side still sees the fields, FN included
        VCard plain = VCardManager.getInstanceFor(workbench).loadVCard(robot.getUser().asEntityBareJid());
        assertEquals("mobile robot (differential drive)", plain.getField("FN"));
        assertEquals("Sabot Robotics", plain.getLastName());
        assertArrayEquals(published.png(), plain.getAvatar());
        assertEquals("image/png", plain.getAvatarMimeType());
    }

    @Test
    void entitiesThatAreNotDevicesAreReportedAsSuch() throws Exception {
        XMPPTCPConnection person = server().login("person-id");
        XMPPTCPConnection nobody = server().login("nobody-id");
        XMPPTCPConnection workbench = server().login("wb2-id");
        VCard human = new VCard();
        human.setFirstName("Ada");
        human.setLastName("Lovelace");
        VCardManager.getInstanceFor(person).saveVCard(human);

        DeviceIdentityManager id = DeviceIdentityManager.getInstanceFor(workbench);
        IdentityResult<DeviceCard> notDevice = id.fetch(person.getUser().asEntityBareJid());
        IdentityResult<DeviceCard> none = id.fetch(nobody.getUser().asEntityBareJid());

        assertEquals(IdentityResult.Problem.NOT_A_DEVICE, notDevice.problemOrNull());
        assertEquals(IdentityResult.Problem.NO_VCARD, none.problemOrNull());
    }
}
