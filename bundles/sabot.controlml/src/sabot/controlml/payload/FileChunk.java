package sabot.controlml.payload;

import java.util.Arrays;
import java.util.Objects;

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
}
