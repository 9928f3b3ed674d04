package sabot.controlml.payload;

import java.util.Arrays;
import java.util.Base64;
import java.util.Objects;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.swe.SweComponent;

/**
 * Part of a file: the answer to {@code get cm.fs.read}, the value of {@code set cm.fs.write}.
 *
 * @param path   the file; never null
 * @param offset where {@code data} starts, bytes
 * @param data   the bytes (at most 32 KiB so that the base64 text fits a payload); never null
 * @param sha256 lower-case hex SHA-256 of {@code data}, checked on decode; never null
 * @param last   true when the chunk reaches the end of the file
 */
public record FileChunk(String path, long offset, byte[] data, String sha256, boolean last) {
    public FileChunk {
        Objects.requireNonNull(path, "path");
        data = data.clone();
        Objects.requireNonNull(sha256, "sha256");
    }

    @Override
    public byte[] data() {
        return data.clone();
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof FileChunk c && c.path.equals(path) && c.offset == offset && Arrays.equals(c.data, data)
                && c.sha256.equals(sha256) && c.last == last;
    }

    @Override
    public int hashCode() {
        return Objects.hash(path, offset, sha256, last) * 31 + Arrays.hashCode(data);
    }

    @Override
    public String toString() {
        return "FileChunk[" + path + " @" + offset + " +" + data.length + (last ? " last" : "") + "]";
    }

    /** Largest chunk, bytes: 32 KiB of data is 43,692 characters of base64, well inside one payload. */
    public static final int MAX_CHUNK = 32 * 1024;

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<FileChunk> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(FileChunk c) {
            return new RecordBuilder().text("path", c.path()).count("offset", c.offset()).text("data", Base64
                    .getEncoder().encodeToString(c.data())).text("sha256", c.sha256()).bool("last", c.last()).build();
        }

        @Override
        public FileChunk decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "path", "offset", "data", "sha256", "last");
            byte[] data;
            try {
                data = Base64.getDecoder().decode(r.text("data", 4 * (MAX_CHUNK / 3 + 1)));
            } catch (IllegalArgumentException e) {
                throw new PayloadException(ControlMlCondition.MALFORMED_PAYLOAD, "data is not base64");
            }
            String sha = r.text("sha256", 64);
            if (!sha.equals(sha256Hex(data))) {
                throw new PayloadException(ControlMlCondition.INVALID_VALUE, "sha256 does not match the data");
            }
            return new FileChunk(FileQuery.path(r), r.count("offset", 0, Long.MAX_VALUE), data, sha, r.bool("last"));
        }
    };

    /** @return lower-case hex SHA-256 of bytes */
    public static String sha256Hex(byte[] data) {
        try {
            byte[] d = java.security.MessageDigest.getInstance("SHA-256").digest(data);
            return java.util.HexFormat.of().formatHex(d);
        } catch (java.security.NoSuchAlgorithmException e) {
            throw new IllegalStateException("SHA-256 is a required JDK algorithm", e);
        }
    }
}
