package sabot.identity.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.awt.image.BufferedImage;
import java.io.ByteArrayOutputStream;

import javax.imageio.ImageIO;

import org.junit.jupiter.api.Test;
import org.osgi.framework.Bundle;
import org.osgi.framework.FrameworkUtil;
import org.osgi.util.tracker.ServiceTracker;

import sabot.identity.IdentityResult;
import sabot.identity.Inventory;
import sabot.identity.InventorySource;
import sabot.identity.InventoryXml;
import sabot.identity.QrInventory;

class QrInventoryTest {

    @Test
    void smallInventoryTravelsAsPlainXmlAnyReaderCanShow() {
        Inventory inv = Fixtures.inventory(3);
        QrInventory.Encoded qr = QrInventory.encode(inv).orElseThrow();

        assertEquals(QrInventory.Form.PLAIN, qr.form());
        assertEquals(InventoryXml.write(inv), QrInventory.readText(qr.png()).orElseThrow(),
                "a generic reader sees the document itself");
        assertEquals(inv, QrInventory.decode(qr.png()).orElseThrow());
    }

    @Test
    void largeInventoryIsDeflatedAndStillDecodesToTheSameDocument() {
        Inventory inv = Fixtures.inventory(90);
        QrInventory.Encoded qr = QrInventory.encode(inv).orElseThrow();

        assertEquals(QrInventory.Form.DEFLATED, qr.form());
        assertTrue(qr.xmlBytes() > 2953, "the plain document would not fit: " + qr.xmlBytes());
        assertTrue(QrInventory.readText(qr.png()).orElseThrow().startsWith(QrInventory.DEFLATED_PREFIX));
        assertEquals(inv, QrInventory.decode(qr.png()).orElseThrow());
    }

    @Test
    void inventoryBeyondQrCapacityIsAClearError() {
        IdentityResult<QrInventory.Encoded> r = QrInventory.encode(Fixtures.inventory(2500));

        assertEquals(IdentityResult.Problem.TOO_LARGE_FOR_QR, r.problemOrNull());
        assertTrue(((IdentityResult.Err<QrInventory.Encoded>) r).text().contains("4296"));
    }

    @Test
    void documentWhoseHashDoesNotMatchIsRejected() {
        String xml = InventoryXml.write(Fixtures.inventory(3)).replace("org.example.library1", "org.evil.library1");
        assertEquals(IdentityResult.Problem.NOT_AN_INVENTORY, QrInventory.fromText(xml).problemOrNull());
        assertEquals(IdentityResult.Problem.NOT_AN_INVENTORY, QrInventory.fromText("hello").problemOrNull());
    }

    @Test
    void imageWithoutQrCodeIsReportedAsSuch() throws Exception {
        BufferedImage blank = new BufferedImage(200, 200, BufferedImage.TYPE_BYTE_BINARY);
        ByteArrayOutputStream png = new ByteArrayOutputStream();
        ImageIO.write(blank, "png", png);
        assertEquals(IdentityResult.Problem.NO_QR_CODE, QrInventory.decode(png.toByteArray()).problemOrNull());
        assertEquals(IdentityResult.Problem.NO_QR_CODE, QrInventory.decode(new byte[] { 1, 2, 3 }).problemOrNull());
    }

    @Test
    void declarativeServicesComponentListsTheRunningFrameworksBundles() throws Exception {
        Bundle identity = FrameworkUtil.getBundle(InventorySource.class);
        identity.start(Bundle.START_ACTIVATION_POLICY); // what the product's config.ini does for lazy bundles
        ServiceTracker<InventorySource, InventorySource> tracker = new ServiceTracker<>(identity.getBundleContext(),
                InventorySource.class, null);
        tracker.open();
        try {
            InventorySource source = tracker.waitForService(10_000);
            assertTrue(source != null, "no InventorySource service (is Felix SCR running?)");
            Inventory inv = source.inventory(Fixtures.hardware(Fixtures.SERIAL));
            Inventory.Board board = inv.boards().get(0);
            assertTrue(board.applications().contains(new Inventory.Item("sabot.identity", identity.getVersion()
                    .toString())), board.applications().toString());
            assertTrue(board.libraries().stream().anyMatch(i -> i.name().equals("smack-core")), "Smack missing");
            assertTrue(board.packages().stream().anyMatch(i -> i.name().equals("org.eclipse.osgi")));
            assertEquals(identity.getBundleContext().getBundles().length - 1, board.applications().size() + board
                    .libraries().size(), "every bundle but the framework is listed once");
            assertEquals(inv, QrInventory.decode(QrInventory.encode(inv).orElseThrow().png()).orElseThrow());
        } finally {
            tracker.close();
        }
    }
}
