package sabot.controlml.payload;

import java.util.Objects;

/**
 * @param name      entry name (no path); never null
 * @param size      bytes (0 for directories)
 * @param directory true for a directory
 */
public record FileEntry(String name, long size, boolean directory) {
    public FileEntry {
        Objects.requireNonNull(name, "name");
    }
}
