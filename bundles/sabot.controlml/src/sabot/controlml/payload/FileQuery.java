package sabot.controlml.payload;

import java.util.Objects;

/**
 * Which file (and which part of it) a {@code cm.fs.*} request is about. Paths are relative to the robot's remote-FS
 * root, {@code /}-separated, without {@code ..}.
 *
 * @param path   the path; never null
 * @param offset first byte, &ge; 0 (0 for list and delete)
 * @param length bytes wanted, &ge; 0 (0 for list and delete)
 */
public record FileQuery(String path, long offset, long length) {
    public FileQuery {
        Objects.requireNonNull(path, "path");
    }
}
