package sabot.onboard.remotefs.internal;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.LinkOption;
import java.nio.file.NoSuchFileException;
import java.nio.file.NotDirectoryException;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;

import sabot.onboard.remotefs.internal.PathRefusal.Reason;

/**
 * The remote-FS root and the only way to turn a requester's path into a {@link Path}: every path handed out lies
 * inside the root after resolving symbolic links. Plain java.nio, no protocol.
 * <p>
 * A remote-FS path is relative, {@code /}-separated, and every segment is a plain name: not empty, not {@code .} or
 * {@code ..}, no backslash, no NUL or other control character, at most {@value #MAX_SEGMENT} characters, and not a
 * name reserved for transfers in progress ({@code .<name>}{@value #PARTIAL_SUFFIX}). The empty path is the root.
 * Links inside the root are followed as long as they end inside the root; a link leading out of it, or to nothing,
 * is refused. (A link created by another onboard process between the check and the use is not guarded against: the
 * root belongs to this service.)
 */
public final class ConfinedRoot {

    /** Suffix of the temporary file a chunked write goes to before it is moved into place. */
    public static final String PARTIAL_SUFFIX = ".sabot-partial";
    /** Longest segment: 255 (the usual file-name limit) minus the partial file's {@code .} and suffix. */
    public static final int MAX_SEGMENT = 240;
    /** Longest path, characters (the protocol's {@code path} Text limit). */
    public static final int MAX_PATH = 512;

    private final Path root;

    /**
     * @param root an existing directory; symbolic links in it are resolved once, here
     * @throws IOException when the root does not exist or is not a directory
     */
    public ConfinedRoot(Path root) throws IOException {
        this.root = root.toRealPath();
        if (!Files.isDirectory(this.root)) {
            throw new NotDirectoryException(root.toString());
        }
    }

    /** @return the root's real path */
    public Path root() {
        return root;
    }

    /**
     * @param path a remote-FS path
     * @return its segments; empty for the root ({@code ""})
     * @throws PathRefusal {@link Reason#MALFORMED} when it is not a remote-FS path
     */
    public static List<String> segments(String path) throws PathRefusal {
        if (path == null) {
            throw new PathRefusal(Reason.MALFORMED, "no path");
        }
        if (path.length() > MAX_PATH) {
            throw new PathRefusal(Reason.MALFORMED, "path longer than " + MAX_PATH + " characters");
        }
        if (path.isEmpty()) {
            return List.of();
        }
        if (path.startsWith("/")) {
            throw new PathRefusal(Reason.MALFORMED, "path '" + path + "' is absolute; paths are relative to the "
                    + "remote-FS root");
        }
        for (int i = 0; i < path.length(); i++) {
            char c = path.charAt(i);
            if (c == '\\') {
                throw new PathRefusal(Reason.MALFORMED, "path '" + path + "' holds a backslash; the separator is '/'");
            }
            if (c < 0x20 || c == 0x7f) {
                throw new PathRefusal(Reason.MALFORMED, "path holds a control character (code " + (int) c + ")");
            }
        }
        List<String> segments = new ArrayList<>();
        for (String s : path.split("/", -1)) {
            if (s.isEmpty()) {
                throw new PathRefusal(Reason.MALFORMED, "path '" + path + "' has an empty segment");
            }
            if (s.equals(".") || s.equals("..")) {
                throw new PathRefusal(Reason.MALFORMED, "path '" + path + "' has a '" + s + "' segment");
            }
            if (s.length() > MAX_SEGMENT) {
                throw new PathRefusal(Reason.MALFORMED, "a segment of the path is longer than " + MAX_SEGMENT
                        + " characters");
            }
            if (isPartialName(s)) {
                throw new PathRefusal(Reason.MALFORMED, "name '" + s + "' is reserved for transfers in progress");
            }
            segments.add(s);
        }
        return segments;
    }

    /** @return true for the name of a transfer's temporary file */
    public static boolean isPartialName(String name) {
        return name.length() > PARTIAL_SUFFIX.length() + 1 && name.startsWith(".") && name.endsWith(PARTIAL_SUFFIX);
    }

    /** @return the temporary file a write to {@code target} goes to: a hidden sibling, so the move is atomic */
    public static Path partialFor(Path target) {
        return target.resolveSibling("." + target.getFileName() + PARTIAL_SUFFIX);
    }

    /**
     * @return the real path of an existing file or directory (links followed), inside the root
     * @throws PathRefusal when the path is malformed, leaves the root, or names nothing
     */
    public Path existing(String path) throws PathRefusal {
        Path current = root;
        List<String> segments = segments(path);
        for (int i = 0; i < segments.size(); i++) {
            current = step(current, segments.get(i), path, i < segments.size() - 1);
        }
        return current;
    }

    /**
     * @return the entry itself, not following a final link (what a delete removes): its parent is a real path inside
     *         the root, and a final link, if any, ends inside the root
     * @throws PathRefusal when the path is malformed, the root itself, leaves the root, or names nothing
     */
    public Path entry(String path) throws PathRefusal {
        List<String> segments = segments(path);
        if (segments.isEmpty()) {
            throw new PathRefusal(Reason.MALFORMED, "the path names the root itself");
        }
        Path parent = root;
        for (int i = 0; i < segments.size() - 1; i++) {
            parent = step(parent, segments.get(i), path, true);
        }
        Path entry = parent.resolve(segments.get(segments.size() - 1));
        step(parent, segments.get(segments.size() - 1), path, false); // the final link's target must be inside too
        return entry;
    }

    /**
     * Where a write of {@code path} lands: its existing directories are resolved (each inside the root), missing ones
     * are returned unresolved for the caller to create, a final link inside the root is followed. Nothing is created
     * or changed here.
     *
     * @return the target file's path (it may exist, be missing, or be a directory the caller refuses)
     * @throws PathRefusal when the path is malformed, the root itself, leaves the root, or runs through a file
     */
    public Path forWrite(String path) throws PathRefusal {
        List<String> segments = segments(path);
        if (segments.isEmpty()) {
            throw new PathRefusal(Reason.MALFORMED, "the path names the root itself");
        }
        Path current = root;
        boolean missing = false;
        for (int i = 0; i < segments.size(); i++) {
            String segment = segments.get(i);
            boolean last = i == segments.size() - 1;
            Path next = current.resolve(segment);
            if (missing || !Files.exists(next, LinkOption.NOFOLLOW_LINKS)) {
                missing = true; // below a missing directory nothing exists yet: no link to follow
                current = next;
            } else {
                current = step(current, segment, path, !last);
            }
        }
        return current;
    }

    /**
     * One segment down from a real directory inside the root.
     *
     * @param mustBeDirectory true for every segment but the last
     */
    private Path step(Path directory, String segment, String path, boolean mustBeDirectory) throws PathRefusal {
        Path next = directory.resolve(segment);
        if (!Files.exists(next, LinkOption.NOFOLLOW_LINKS)) {
            throw new PathRefusal(Reason.NOT_FOUND, "no file or directory '" + path + "'");
        }
        Path real;
        try {
            real = next.toRealPath();
        } catch (NoSuchFileException e) {
            throw new PathRefusal(Reason.OUTSIDE_ROOT, "path '" + path + "' runs through a link that points nowhere");
        } catch (IOException e) {
            throw new PathRefusal(Reason.OUTSIDE_ROOT, "path '" + path + "' cannot be resolved: " + e.getMessage());
        }
        if (!real.startsWith(root)) {
            throw new PathRefusal(Reason.OUTSIDE_ROOT, "path '" + path + "' leads outside the remote-FS root");
        }
        if (mustBeDirectory && !Files.isDirectory(real)) {
            throw new PathRefusal(Reason.NOT_A_DIRECTORY, "'" + segment + "' in path '" + path
                    + "' is a file, not a directory");
        }
        return real;
    }
}
