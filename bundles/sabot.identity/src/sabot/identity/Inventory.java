package sabot.identity;

import java.nio.charset.StandardCharsets;
import java.security.MessageDigest;
import java.security.NoSuchAlgorithmException;
import java.util.Base64;
import java.util.List;
import java.util.Objects;

/**
 * What a device is made of: the QR-Code inventory document (see {@code docs/IDENTITY.md} for its DTD).
 *
 * @param version        the document format version (currently 1)
 * @param uid            the device's {@code urn:uuid:} URN
 * @param mechanic       the mechanical description; never null
 * @param boards         the electronic boards with their software; never empty
 * @param specialDevices peripherals (motor boards, sensors) on their buses; never null
 */
public record Inventory(int version, String uid, Mechanic mechanic, List<Board> boards,
        List<SpecialDevice> specialDevices) {

    /**
     * @param model the chassis model; never null
     * @param parts named mechanical properties with units in their values, e.g. {@code wheel.radius = 0.075 m}
     */
    public record Mechanic(String model, List<Part> parts) {
        public Mechanic {
            Objects.requireNonNull(model, "model");
            parts = List.copyOf(parts);
        }
    }

    /** @param name property name @param value value with unit */
    public record Part(String name, String value) {
        public Part {
            Objects.requireNonNull(name, "name");
            Objects.requireNonNull(value, "value");
        }
    }

    /** A named software item: symbolic name and version. */
    public record Item(String name, String version) {
        public Item {
            Objects.requireNonNull(name, "name");
            Objects.requireNonNull(version, "version");
        }
    }

    /**
     * An electronic board and the software on it.
     *
     * @param name         board name; never null
     * @param cpu          processor description; never null, may be empty
     * @param bsp          the board support package (operating system); may be null
     * @param packages     platform packages (runtime, framework)
     * @param applications Sabot's own bundles
     * @param libraries    third-party bundles
     */
    public record Board(String name, String cpu, Item bsp, List<Item> packages, List<Item> applications,
            List<Item> libraries) {
        public Board {
            Objects.requireNonNull(name, "name");
            Objects.requireNonNull(cpu, "cpu");
            packages = List.copyOf(packages);
            applications = List.copyOf(applications);
            libraries = List.copyOf(libraries);
        }
    }

    /**
     * @param name    device name (e.g. {@code SACT motor board}); never null
     * @param model   model; never null, may be empty
     * @param bus     bus (e.g. {@code RS485}); never null, may be empty
     * @param address address on the bus (e.g. {@code 0x14}); never null, may be empty
     */
    public record SpecialDevice(String name, String model, String bus, String address) {
        public SpecialDevice {
            Objects.requireNonNull(name, "name");
            Objects.requireNonNull(model, "model");
            Objects.requireNonNull(bus, "bus");
            Objects.requireNonNull(address, "address");
        }
    }

    public Inventory {
        Objects.requireNonNull(uid, "uid");
        Objects.requireNonNull(mechanic, "mechanic");
        boards = List.copyOf(boards);
        specialDevices = List.copyOf(specialDevices);
        if (boards.isEmpty()) {
            throw new IllegalArgumentException("at least one board");
        }
    }

    /**
     * The content hash of the ELECTRONIC section: SHA-256 over one line per software item,
     * {@code board/kind/name/version\n} in document order, base64url without padding (43 characters). A reader
     * recomputes it to check that the document it decoded is the one that was encoded.
     */
    public String electronicHash() {
        StringBuilder canonical = new StringBuilder();
        for (Board b : boards) {
            if (b.bsp() != null) {
                line(canonical, b, "BSP", b.bsp());
            }
            b.packages().forEach(i -> line(canonical, b, "PACKAGE", i));
            b.applications().forEach(i -> line(canonical, b, "APPLICATION", i));
            b.libraries().forEach(i -> line(canonical, b, "LIBRARY", i));
        }
        try {
            byte[] d = MessageDigest.getInstance("SHA-256").digest(canonical.toString().getBytes(
                    StandardCharsets.UTF_8));
            return Base64.getUrlEncoder().withoutPadding().encodeToString(d);
        } catch (NoSuchAlgorithmException e) {
            throw new IllegalStateException("SHA-256 is a required JDK algorithm", e);
        }
    }

    private static void line(StringBuilder sb, Board b, String kind, Item i) {
        sb.append(b.name()).append('/').append(kind).append('/').append(i.name()).append('/').append(i.version())
                .append('\n');
    }
}
