package sabot.controlml.payload;

import java.util.Objects;
import java.util.regex.Pattern;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.swe.SweComponent;

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

    // Relative, '/'-separated, no '..', no empty segments except the root "".
    private static final Pattern PATH = Pattern.compile("|[A-Za-z0-9_.+-]+(/[A-Za-z0-9_.+-]+)*");

    /** @return the {@code path} field of a {@code cm.fs.*} payload, checked */
    static String path(RecordReader r) throws PayloadException {
        String p = r.text("path", 512);
        if (!PATH.matcher(p).matches() || p.equals("..") || p.startsWith("../") || p.contains("/../") || p.endsWith(
                "/..")) {
            throw new PayloadException(ControlMlCondition.INVALID_VALUE, "path '" + p
                    + "' must be relative, '/'-separated, without '..'");
        }
        return p;
    }

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<FileQuery> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(FileQuery q) {
            return new RecordBuilder().text("path", q.path()).count("offset", q.offset()).count("length", q.length())
                    .build();
        }

        @Override
        public FileQuery decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "path", "offset", "length");
            return new FileQuery(path(r), r.count("offset", 0, Long.MAX_VALUE), r.count("length", 0,
                    FileChunk.MAX_CHUNK));
        }
    };
}
