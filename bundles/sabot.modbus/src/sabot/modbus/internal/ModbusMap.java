package sabot.modbus.internal;

import java.io.IOException;
import java.io.InputStream;
import java.io.InputStreamReader;
import java.io.Reader;
import java.io.UncheckedIOException;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;

import com.google.gson.JsonArray;
import com.google.gson.JsonElement;
import com.google.gson.JsonObject;
import com.google.gson.JsonParser;

/**
 * The register map of the robot's RS-485 bus, read from {@code docs/sact-modbus-map.json}: the one source the C
 * firmware's register tables are generated from. The build copies the file into this bundle's root; nothing here
 * knows a register number of its own.
 */
public final class ModbusMap {

    /** Where the build puts the map inside the bundle. */
    public static final String RESOURCE = "/sact-modbus-map.json";
    private static final String FORMAT = "sabot-modbus-map/2";

    private static volatile ModbusMap standard;

    private final Map<String, Integer> slaves = new HashMap<>();
    private final Map<String, Field> fields = new HashMap<>();
    private final JsonObject protocol;
    private final JsonObject control;

    /**
     * One record (or run of records, see {@link #count}) of one file of one board. A robot constant has no literal
     * {@code defaultValue}: {@code defaultFrom} names its key in docs/sabot-robot.properties and the power-on value is
     * that value times {@code defaultFactor}; for other records {@code defaultFrom} is null.
     */
    public record Field(String board, int slave, String fileName, int file, String name, int record, String type,
            int count, boolean writable, long min, long max, String maxFrom, long defaultValue, String defaultFrom,
            long defaultFactor, double scale, String siUnit, Map<String, Integer> bits) {

        /** @return registers one value takes: 2 for 32-bit types, else 1 */
        public int width() {
            return type.endsWith("32") ? 2 : 1;
        }

        /** @return registers the whole field takes ({@code count} values) */
        public int registers() {
            return width() * count;
        }

        /**
         * Decodes the value at {@code regs[offset]} (high word first for 32-bit types).
         *
         * @return the raw register value, sign-extended for signed types
         */
        public long decode(short[] regs, int offset) {
            return switch (type) {
                case "int16" -> regs[offset];
                case "uint16" -> regs[offset] & 0xFFFF;
                case "int32" -> ((regs[offset] & 0xFFFF) << 16) | (regs[offset + 1] & 0xFFFF);
                case "uint32" -> (((long) regs[offset] & 0xFFFF) << 16) | (regs[offset + 1] & 0xFFFF);
                default -> throw new IllegalStateException("unknown register type " + type + " of " + this);
            };
        }

        /** @return {@code raw} × scale: the value in {@link #siUnit} */
        public double si(long raw) {
            return raw * scale;
        }

        /**
         * Checks {@code raw} against the static bounds of the map.
         *
         * @throws IllegalArgumentException naming the record, the value and the bounds
         */
        public void checkBounds(String what, long raw) {
            if (raw < min || raw > max) {
                throw new IllegalArgumentException(String.format("%s: %d is outside %s/%s/%s's bounds [%d, %d]",
                        what, raw, board, fileName, name, min, max));
            }
        }

        /**
         * The raw register value of an SI value: {@code si} / scale, rounded, checked against the static bounds.
         *
         * @param what names the value in the message
         * @throws IllegalArgumentException when {@code si} is not finite or the raw value is out of bounds, naming
         *                                  {@code what}, the value and the bounds
         */
        public long raw(String what, double si) {
            if (!Double.isFinite(si)) {
                throw new IllegalArgumentException(what + " is " + si + " " + siUnit);
            }
            long raw = Math.round(si / scale);
            checkBounds(what + " " + si + " " + siUnit, raw);
            return raw;
        }

        /** @return the 16-bit register words of {@code raw} (high word first for 32-bit types) */
        public short[] encode(long raw) {
            return width() == 2 ? new short[] { (short) (raw >>> 16), (short) raw } : new short[] { (short) raw };
        }

        /** @return the bit number of a named flag of this record */
        public int bit(String flag) {
            Integer b = bits.get(flag);
            if (b == null) {
                throw new IllegalStateException("the map names no bit '" + flag + "' in " + board + "/" + fileName
                        + "/" + name);
            }
            return b;
        }
    }

    private ModbusMap(JsonObject root) {
        String format = root.get("format").getAsString();
        if (!FORMAT.equals(format)) {
            throw new IllegalStateException("register map format " + format + ", expected " + FORMAT);
        }
        protocol = root.getAsJsonObject("protocol");
        control = root.getAsJsonObject("control");
        for (JsonElement b : root.getAsJsonArray("boards")) {
            JsonObject board = b.getAsJsonObject();
            String boardName = board.get("name").getAsString();
            int slave = board.get("slave_address").getAsInt();
            slaves.put(boardName, slave);
            JsonObject templates = board.has("templates") ? board.getAsJsonObject("templates") : new JsonObject();
            for (JsonElement f : board.getAsJsonArray("files")) {
                JsonObject file = f.getAsJsonObject();
                String fileName = file.get("name").getAsString();
                int fileNumber = file.get("file").getAsInt();
                JsonArray records = file.has("template")
                        ? templates.getAsJsonArray(file.get("template").getAsString())
                        : file.getAsJsonArray("records");
                for (JsonElement r : records) {
                    JsonObject rec = r.getAsJsonObject();
                    Map<String, Integer> bits = new HashMap<>();
                    if (rec.has("bits")) {
                        rec.getAsJsonObject("bits").entrySet()
                                .forEach(e -> bits.put(e.getKey(), e.getValue().getAsInt()));
                    }
                    Field field = new Field(boardName, slave, fileName, fileNumber, rec.get("name").getAsString(),
                            rec.get("record").getAsInt(), rec.get("type").getAsString(),
                            rec.has("count") ? rec.get("count").getAsInt() : 1,
                            rec.get("access").getAsString().contains("w"), rec.get("min").getAsLong(),
                            rec.get("max").getAsLong(), rec.has("max_from") ? rec.get("max_from").getAsString() : null,
                            rec.has("default") ? rec.get("default").getAsLong() : 0,
                            rec.has("default_from") ? rec.getAsJsonObject("default_from").get("robot").getAsString()
                                    : null,
                            rec.has("default_from") ? rec.getAsJsonObject("default_from").get("factor").getAsLong()
                                    : 1,
                            rec.get("scale").getAsDouble(),
                            rec.get("si_unit").getAsString(), Map.copyOf(bits));
                    fields.put(key(boardName, fileName, field.name()), field);
                }
            }
        }
    }

    private static String key(String board, String file, String record) {
        return board + "/" + file + "/" + record;
    }

    /** @return the map packaged in this bundle (parsed once) */
    public static ModbusMap standard() {
        ModbusMap m = standard;
        if (m == null) {
            try (InputStream in = ModbusMap.class.getResourceAsStream(RESOURCE)) {
                if (in == null) {
                    throw new IllegalStateException("the register map " + RESOURCE
                            + " is missing from the sabot.modbus bundle (the build copies docs/sact-modbus-map.json)");
                }
                m = parse(new InputStreamReader(in, StandardCharsets.UTF_8));
            } catch (IOException e) {
                throw new UncheckedIOException("cannot read the register map " + RESOURCE, e);
            }
            standard = m;
        }
        return m;
    }

    /** @return the map read from {@code json} */
    public static ModbusMap parse(Reader json) {
        return new ModbusMap(JsonParser.parseReader(json).getAsJsonObject());
    }

    /** @return the slave address of a board */
    public int slave(String board) {
        Integer s = slaves.get(board);
        if (s == null) {
            throw new IllegalArgumentException("the register map has no board '" + board + "'");
        }
        return s;
    }

    /** @return the field (board, file name, record name) */
    public Field field(String board, String file, String record) {
        Field f = fields.get(key(board, file, record));
        if (f == null) {
            throw new IllegalArgumentException("the register map has no record " + key(board, file, record));
        }
        return f;
    }

    /** @return whether the map has the field */
    public boolean has(String board, String file, String record) {
        return fields.containsKey(key(board, file, record));
    }

    /** @return all fields of one file, by record number */
    public List<Field> file(String board, String file) {
        List<Field> list = new ArrayList<>();
        for (Field f : fields.values()) {
            if (f.board().equals(board) && f.fileName().equals(file)) {
                list.add(f);
            }
        }
        list.sort((a, b) -> Integer.compare(a.record(), b.record()));
        return list;
    }

    private JsonObject serial() {
        return protocol.getAsJsonObject("serial");
    }

    /** @return the line's baud rate */
    public int baud() {
        return serial().get("baud").getAsInt();
    }

    /** @return the line's parity letter: N, E or O */
    public String parity() {
        return serial().get("parity").getAsString();
    }

    /** @return bits one character takes on the line: start + data + parity + stop (11 for 8E1) */
    public int bitsPerCharacter() {
        return 1 + serial().get("data_bits").getAsInt() + ("N".equals(parity()) ? 0 : 1)
                + serial().get("stop_bits").getAsInt();
    }

    /** @return the silence that ends a frame above 19200 baud (t3.5) */
    public Duration t35() {
        return Duration.ofNanos(serial().get("t3_5_us").getAsLong() * 1000);
    }

    /** @return the reference type of every file-record sub-request */
    public int referenceType() {
        return protocol.get("reference_type").getAsInt();
    }

    /** @return a Modbus exception code by its map name (e.g. illegal_data_value) */
    public int exception(String name) {
        return Objects.requireNonNull(protocol.getAsJsonObject("exceptions").get(name), name).getAsInt();
    }

    /** @return encoder counts per encoder line (4: quadrature) */
    public int quadrature() {
        return control.get("quadrature").getAsInt();
    }
}
