package sabot.controlml.payload;

import java.util.ArrayList;
import java.util.List;
import java.util.Objects;

import sabot.controlml.swe.SweComponent;

/** {@code cm.fs.list}'s answer. @param path the directory @param entries its entries; never null */
public record DirectoryListing(String path, List<FileEntry> entries) {
    public DirectoryListing {
        Objects.requireNonNull(path, "path");
        entries = List.copyOf(entries);
    }

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<DirectoryListing> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(DirectoryListing l) {
            RecordBuilder b = new RecordBuilder().text("path", l.path()).count("count", l.entries().size());
            int i = 0;
            for (FileEntry e : l.entries()) {
                b.add("entry" + i++, new RecordBuilder().text("name", e.name()).count("size", e.size()).bool(
                        "directory", e.directory()).build());
            }
            return b.build();
        }

        @Override
        public DirectoryListing decode(SweComponent payload) throws PayloadException {
            String[] indexed = RecordReader.indexedFields(payload, "entry", 1024);
            String[] names = new String[indexed.length + 1];
            names[0] = "path";
            System.arraycopy(indexed, 0, names, 1, indexed.length);
            RecordReader r = RecordReader.of(payload, names);
            List<FileEntry> entries = new ArrayList<>();
            for (int i = 2; i < names.length; i++) {
                RecordReader e = r.record(names[i], "name", "size", "directory");
                entries.add(new FileEntry(e.text("name", 255), e.count("size", 0, Long.MAX_VALUE), e.bool(
                        "directory")));
            }
            return new DirectoryListing(FileQuery.path(r), entries);
        }
    };
}
