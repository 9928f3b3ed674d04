package sabot.identity;

import java.nio.charset.StandardCharsets;
import java.security.MessageDigest;
import java.security.NoSuchAlgorithmException;
import java.util.Objects;
import java.util.UUID;

/**
 * A device's permanent identifier: an RFC 4122 version-5 (SHA-1, name-based) UUID of its serial number in the Sabot
 * namespace, written as the URN {@code urn:uuid:...} (RFC 4122 section 3) in the vCard's UID.
 * <p>
 * The Sabot namespace is itself the version-5 UUID of the URL {@code https://sabot.invalid/device} in RFC 4122's URL
 * namespace ({@value #NAMESPACE_STRING}), so anyone can recompute a device's UUID from its serial without Sabot code.
 */
public final class DeviceUrn {

    /** RFC 4122 appendix C: the namespace for URLs. */
    public static final UUID URL_NAMESPACE = UUID.fromString("6ba7b811-9dad-11d1-80b4-00c04fd430c8");
    /** The Sabot device namespace, as text. */
    public static final String NAMESPACE_STRING = "uuid5(URL, 'https://sabot.invalid/device')";
    /** The Sabot device namespace. */
    public static final UUID NAMESPACE = nameBased(URL_NAMESPACE, "https://sabot.invalid/device");

    private DeviceUrn() {
    }

    /**
     * @param serial the device's serial number, as printed on its label (UTF-8; compared exactly)
     * @return its UUID (version 5, variant RFC 4122)
     */
    public static UUID uuidOf(String serial) {
        if (Objects.requireNonNull(serial, "serial").isBlank()) {
            throw new IllegalArgumentException("blank serial");
        }
        return nameBased(NAMESPACE, serial);
    }

    /** @return {@code urn:uuid:<uuid>} of a serial */
    public static String urnOf(String serial) {
        return "urn:uuid:" + uuidOf(serial);
    }

    /** @return the UUID of a {@code urn:uuid:} URN, or null when the text is not one */
    public static UUID parseUrn(String urn) {
        if (urn == null || !urn.regionMatches(true, 0, "urn:uuid:", 0, 9)) {
            return null;
        }
        try {
            return UUID.fromString(urn.substring(9));
        } catch (IllegalArgumentException e) {
            return null;
        }
    }

    /** RFC 4122 section 4.3 with SHA-1: hash(namespace bytes + name bytes), version 5, RFC 4122 variant. */
    public static UUID nameBased(UUID namespace, String name) {
        MessageDigest sha1;
        try {
            sha1 = MessageDigest.getInstance("SHA-1");
        } catch (NoSuchAlgorithmException e) {
            throw new IllegalStateException("SHA-1 is a required JDK algorithm", e);
        }
        sha1.update(toBytes(namespace.getMostSignificantBits()));
        sha1.update(toBytes(namespace.getLeastSignificantBits()));
        byte[] h = sha1.digest(name.getBytes(StandardCharsets.UTF_8));
        h[6] = (byte) ((h[6] & 0x0f) | 0x50); // version 5
        h[8] = (byte) ((h[8] & 0x3f) | 0x80); // variant 10x
        long msb = 0;
        long lsb = 0;
        for (int i = 0; i < 8; i++) {
            msb = (msb << 8) | (h[i] & 0xff);
        }
        for (int i = 8; i < 16; i++) {
            lsb = (lsb << 8) | (h[i] & 0xff);
        }
        return new UUID(msb, lsb);
    }

    private static byte[] toBytes(long v) {
        byte[] b = new byte[8];
        for (int i = 7; i >= 0; i--) {
            b[i] = (byte) v;
            v >>>= 8;
        }
        return b;
    }
}
