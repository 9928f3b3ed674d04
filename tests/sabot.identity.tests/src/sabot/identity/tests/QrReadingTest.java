package sabot.identity.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

import sabot.identity.IdentityResult;
import sabot.identity.Inventory;
import sabot.identity.QrInventory;

/**
 * Inventories of growing size, through every QR version from mid-size to the capacity, read back. (Without the
 * pure-barcode pass the reader missed the 84-library inventory, a 117-module symbol.)
 */
class QrReadingTest {

    @Test
    void everyInventorySizeUpToTheQrCapacityDecodesBack() {
        int decoded = 0;
        for (int libraries = 30; libraries <= 400; libraries += 6) {
            Inventory inventory = Fixtures.inventory(libraries);
            IdentityResult<QrInventory.Encoded> qr = QrInventory.encode(inventory);
            if (qr instanceof IdentityResult.Err<QrInventory.Encoded> tooBig) {
                assertEquals(IdentityResult.Problem.TOO_LARGE_FOR_QR, tooBig.problem());
                break;
            }
            IdentityResult<Inventory> back = QrInventory.decode(qr.orElseThrow().png());
            assertTrue(back instanceof IdentityResult.Ok, libraries + " libraries, " + qr.orElseThrow().modules()
                    + " modules: " + back);
            assertEquals(inventory, back.orElseThrow());
            decoded++;
        }
        assertTrue(decoded > 15, "only " + decoded + " sizes tried before the capacity");
    }
}
