package sabot.identity.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.UUID;

import org.junit.jupiter.api.Test;

import sabot.identity.DeviceUrn;

class DeviceUrnTest {

    @Test
    void nameBasedUuidMatchesRfc4122Version5ReferenceValue() {
        // uuid.uuid5(uuid.NAMESPACE_DNS, "python.org") in CPython's reference implementation
        UUID dns = UUID.fromString("6ba7b810-9dad-11d1-80b4-00c04fd430c8");
        assertEquals(UUID.fromString("886313e1-3b8a-5372-9b90-0c9aee199e5d"), DeviceUrn.nameBased(dns, "python.org"));
    }

    @Test
    void deviceUuidIsVersion5VariantRfc4122AndStablePerSerial() {
        UUID a = DeviceUrn.uuidOf("SBT-2026-0042");
        assertEquals(5, a.version());
        assertEquals(2, a.variant());
        assertEquals(a, DeviceUrn.uuidOf("SBT-2026-0042"));
        assertNotEquals(a, DeviceUrn.uuidOf("SBT-2026-0043"));
        assertEquals(DeviceUrn.nameBased(DeviceUrn.URL_NAMESPACE, "https://sabot.invalid/device"), DeviceUrn.NAMESPACE);
    }

    @Test
    void urnRoundTrips() {
        String urn = DeviceUrn.urnOf("SBT-2026-0042");
        assertTrue(urn.startsWith("urn:uuid:"));
        assertEquals(DeviceUrn.uuidOf("SBT-2026-0042"), DeviceUrn.parseUrn(urn));
        assertNull(DeviceUrn.parseUrn("urn:isbn:123"));
        assertNull(DeviceUrn.parseUrn("urn:uuid:not-a-uuid"));
    }
}
