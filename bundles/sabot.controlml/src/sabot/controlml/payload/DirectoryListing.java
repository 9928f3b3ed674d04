package sabot.controlml.payload;

import java.util.List;
import java.util.Objects;

/** {@code cm.fs.list}'s answer. @param path the directory @param entries its entries; never null */
public record DirectoryListing(String path, List<FileEntry> entries) {
    public DirectoryListing {
        Objects.requireNonNull(path, "path");
        entries = List.copyOf(entries);
    }
}
