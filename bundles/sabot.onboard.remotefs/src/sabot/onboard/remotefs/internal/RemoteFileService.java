package sabot.onboard.remotefs.internal;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.ByteBuffer;
import java.nio.channels.FileChannel;
import java.nio.file.DirectoryNotEmptyException;
import java.nio.file.Files;
import java.nio.file.LinkOption;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;
import java.nio.file.StandardCopyOption;
import java.nio.file.StandardOpenOption;
import java.nio.file.attribute.BasicFileAttributes;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.Comparator;
import java.util.Iterator;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.stream.Stream;

import org.jivesoftware.smack.packet.StanzaError;
import org.jxmpp.jid.Jid;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.ControlMl;
import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlError;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.payload.DirectoryListing;
import sabot.controlml.payload.FileChunk;
import sabot.controlml.payload.FileEntry;
import sabot.controlml.payload.FileQuery;
import sabot.controlml.swe.SweXml;

/**
 * The robot's remote file system: serves {@code cm.fs.list}, {@code cm.fs.read}, {@code cm.fs.write} and
 * {@code cm.fs.delete} on one onboard root directory (see {@code docs/CONTROLML.md}, "Remote FS service").
 * <p>
 * Every path is confined to the root ({@link ConfinedRoot}). A write arrives in chunks, in order, each with its
 * SHA-256; the bytes go to a hidden temporary file next to the target, which is moved over the target atomically when
 * the {@code last} chunk has arrived, so a reader sees the old file or the whole new one, and an interrupted transfer
 * never leaves a half file under the target's name. A refused request changes nothing on disk.
 * <p>
 * Thread-safe: reads and listings run concurrently; writes and deletes are serialised on one lock (a chunk is at most
 * 32 KiB, so the lock is held for one small write).
 */
public final class RemoteFileService {

    private static final Logger LOGGER = LoggerFactory.getLogger(RemoteFileService.class);

    private final ConfinedRoot root;
    private final RemoteFsLimits limits;

    private final Object writeLock = new Object();
    /** Writes in progress by target path, least recently used first. Guarded by {@link #writeLock}. */
    private final Map<Path, Transfer> transfers = new LinkedHashMap<>(16, 0.75f, true);

    /** A write in progress: who sends it, where its bytes go, how many arrived. */
    private static final class Transfer {
        final Jid requester;
        final Path partial;
        long written;

        Transfer(Jid requester, Path partial, long written) {
            this.requester = requester;
            this.partial = partial;
            this.written = written;
        }
    }

    /**
     * @param root   the directory the remote FS shows; must exist
     * @param limits chunk, file and page limits, read-only flag
     * @throws IOException when the root does not exist or is not a directory
     */
    public RemoteFileService(Path root, RemoteFsLimits limits) throws IOException {
        this.root = new ConfinedRoot(root);
        this.limits = Objects.requireNonNull(limits, "limits");
    }

    /** @return the root's real path */
    public Path root() {
        return root.root();
    }

    /** @return the limits in force */
    public RemoteFsLimits limits() {
        return limits;
    }

    /** Serves the four {@code cm.fs.*} resources on a connection's ControlML endpoint (replacing earlier handlers). */
    public void register(ControlMlManager manager) {
        manager.onGet(Resources.FS_LIST, (request, query) -> list(query));
        manager.onGet(Resources.FS_READ, (request, query) -> read(query));
        manager.onSet(Resources.FS_WRITE, (request, chunk) -> write(request.from(), chunk));
        manager.onSet(Resources.FS_DELETE, (request, query) -> delete(query));
    }

    /** Stops serving the {@code cm.fs.*} resources on a connection's endpoint; transfers in progress stay resumable. */
    public void unregister(ControlMlManager manager) {
        manager.removeHandlers(Resources.FS_LIST);
        manager.removeHandlers(Resources.FS_READ);
        manager.removeHandlers(Resources.FS_WRITE);
        manager.removeHandlers(Resources.FS_DELETE);
    }

    /** @return the number of writes started and not yet completed or abandoned */
    public int transfersInProgress() {
        synchronized (writeLock) {
            return transfers.size();
        }
    }

    // ---------------------------------------------------------------------------------------------- list

    /**
     * {@code cm.fs.list}: the entries of a directory sorted by name ({@link String#compareTo}), from entry number
     * {@code offset}, at most {@code length} of them ({@code 0}: as many as a page holds,
     * {@link RemoteFsLimits#maxListPage}); a page holds fewer when its names would not fit one payload, so the listing
     * ends with the first empty page (an offset at or past the end). Temporary files of
     * transfers in progress, entries whose names are not remote-FS names, and links leading out of the root are not
     * listed. A directory's size is 0; a link inside the root is shown as what it points to.
     */
    public Outcome<DirectoryListing> list(FileQuery query) {
        if (query.offset() < 0 || query.length() < 0) {
            return Outcome.failure(ControlMlCondition.INVALID_VALUE, "offset and length must be >= 0");
        }
        Path directory;
        try {
            directory = root.existing(query.path());
        } catch (PathRefusal e) {
            return refused(e);
        }
        if (!Files.isDirectory(directory)) {
            return Outcome.failure(ControlMlCondition.INVALID_VALUE, "'" + query.path()
                    + "' is a file, not a directory; read it with cm.fs.read");
        }
        List<FileEntry> entries = new ArrayList<>();
        try (Stream<Path> children = Files.list(directory)) {
            for (Iterator<Path> it = children.iterator(); it.hasNext();) {
                FileEntry entry = entryOf(it.next());
                if (entry != null) {
                    entries.add(entry);
                }
            }
        } catch (IOException | UncheckedIOException e) {
            return fault("listing '" + query.path() + "' failed", e);
        }
        entries.sort(Comparator.comparing(FileEntry::name));
        int page = query.length() == 0 ? limits.maxListPage() : (int) Math.min(query.length(), limits
                .maxListPage());
        int from = (int) Math.min(query.offset(), entries.size());
        int count = (int) Math.min(page, entries.size() - from);
        int chars;
        while (count > 1 && (chars = payloadChars(query.path(), entries.subList(from, from + count))) > PAGE_BUDGET) {
            count = (int) ((long) count * PAGE_BUDGET / chars); // strictly fewer each time
        }
        return Outcome.success(new DirectoryListing(query.path(), entries.subList(from, from + count)));
    }

    /**
     * Characters a page may take: one payload ({@link ControlMl#MAX_PAYLOAD_CHARS}) less room for the element around
     * it. Long names, or names full of characters XML escapes, make a page hold fewer entries than asked for.
     */
    static final int PAGE_BUDGET = ControlMl.MAX_PAYLOAD_CHARS - 4096;

    private static int payloadChars(String path, List<FileEntry> entries) {
        StringBuilder xml = new StringBuilder();
        SweXml.write(Resources.FS_LIST.codec().encode(new DirectoryListing(path, entries)), xml);
        return xml.length();
    }

    /** @return the entry as listed, or null when the listing leaves it out */
    private FileEntry entryOf(Path child) {
        String name = child.getFileName().toString();
        try {
            if (ConfinedRoot.segments(name).size() != 1) {
                return null;
            }
        } catch (PathRefusal e) {
            return null; // a transfer's temporary file, or a name no request could address
        }
        try {
            if (Files.isSymbolicLink(child) && !child.toRealPath().startsWith(root.root())) {
                return null;
            }
            BasicFileAttributes a = Files.readAttributes(child, BasicFileAttributes.class);
            return new FileEntry(name, a.isDirectory() ? 0 : a.size(), a.isDirectory());
        } catch (IOException e) {
            return null; // a link to nothing, or an entry deleted while listing
        }
    }

    // ---------------------------------------------------------------------------------------------- read

    /**
     * {@code cm.fs.read}: up to {@code length} bytes from {@code offset} ({@code 0}: as many as a chunk holds,
     * {@link RemoteFsLimits#maxChunk}), with their SHA-256; {@code last} is true when the chunk reaches the end of the
     * file. Reading at the end gives an empty last chunk; past the end is an error.
     */
    public Outcome<FileChunk> read(FileQuery query) {
        if (query.offset() < 0 || query.length() < 0) {
            return Outcome.failure(ControlMlCondition.INVALID_VALUE, "offset and length must be >= 0");
        }
        Path file;
        try {
            file = root.existing(query.path());
        } catch (PathRefusal e) {
            return refused(e);
        }
        if (Files.isDirectory(file)) {
            return Outcome.failure(ControlMlCondition.INVALID_VALUE, "'" + query.path()
                    + "' is a directory; list it with cm.fs.list");
        }
        if (!Files.isRegularFile(file)) {
            return Outcome.failure(ControlMlCondition.INVALID_VALUE, "'" + query.path() + "' is not a regular file");
        }
        int wanted = query.length() == 0 ? limits.maxChunk() : (int) Math.min(query.length(), limits.maxChunk());
        try (FileChannel channel = FileChannel.open(file, StandardOpenOption.READ)) {
            long size = channel.size();
            if (query.offset() > size) {
                return Outcome.failure(ControlMlCondition.INVALID_VALUE, "offset " + query.offset()
                        + " is past the end of '" + query.path() + "' (" + size + " bytes)");
            }
            ByteBuffer buffer = ByteBuffer.allocate((int) Math.min(wanted, size - query.offset()));
            while (buffer.hasRemaining() && channel.read(buffer, query.offset() + buffer.position()) >= 0) {
                // a short read is continued; -1 (the file shrank meanwhile) ends the chunk early
            }
            byte[] data = Arrays.copyOf(buffer.array(), buffer.position());
            return Outcome.success(new FileChunk(query.path(), query.offset(), data, FileChunk.sha256Hex(data), query
                    .offset() + data.length >= size));
        } catch (NoSuchFileException e) {
            return notFound("no file '" + query.path() + "'");
        } catch (IOException e) {
            return fault("reading '" + query.path() + "' failed", e);
        }
    }

    // ---------------------------------------------------------------------------------------------- write

    /**
     * {@code cm.fs.write}: one chunk of a file. A chunk at offset 0 starts a transfer (replacing one in progress for
     * the same file, and a stale temporary file); every further chunk must come from the same requester at the offset
     * equal to the bytes received so far. The {@code last} chunk moves the file into place atomically (replacing an
     * existing file). Missing directories on the way are created with the first chunk. A refused chunk writes
     * nothing and leaves the transfer as it was.
     *
     * @param requester who sends the chunk (a transfer belongs to one requester)
     * @return {@link Outcome#done()} or why not
     */
    public Outcome<FileChunk> write(Jid requester, FileChunk chunk) {
        Objects.requireNonNull(requester, "requester");
        if (limits.readOnly()) {
            return Outcome.failure(ControlMlCondition.SET_NOT_PERMITTED, "the remote FS of this robot is read-only");
        }
        byte[] data = chunk.data();
        if (data.length > limits.maxChunk()) {
            return Outcome.failure(ControlMlCondition.PAYLOAD_TOO_LARGE, "chunk of " + data.length
                    + " bytes; this robot takes at most " + limits.maxChunk() + " bytes a chunk");
        }
        if (!FileChunk.sha256Hex(data).equals(chunk.sha256())) {
            return Outcome.failure(ControlMlCondition.INVALID_VALUE, "sha256 does not match the chunk's data");
        }
        if (chunk.offset() < 0) {
            return Outcome.failure(ControlMlCondition.INVALID_VALUE, "offset must be >= 0");
        }
        if (chunk.offset() > limits.maxFileSize() - data.length) {
            return Outcome.failure(ControlMlCondition.PAYLOAD_TOO_LARGE, "'" + chunk.path() + "' would exceed "
                    + limits.maxFileSize() + " bytes, the largest file this robot takes");
        }
        Path target;
        try {
            target = root.forWrite(chunk.path());
        } catch (PathRefusal e) {
            return refused(e);
        }
        synchronized (writeLock) {
            if (Files.isDirectory(target, LinkOption.NOFOLLOW_LINKS)) {
                return Outcome.failure(ControlMlCondition.INVALID_VALUE, "'" + chunk.path() + "' is a directory");
            }
            Transfer transfer = transfers.get(target);
            if (chunk.offset() == 0) {
                if (transfer != null) {
                    transfers.remove(target); // its temporary file is the one start truncates
                }
                return start(requester, target, chunk, data);
            }
            if (transfer == null) {
                return Outcome.failure(ControlMlCondition.INVALID_STATE, "no transfer of '" + chunk.path()
                        + "' in progress; a transfer starts at offset 0");
            }
            if (!transfer.requester.equals(requester)) {
                return Outcome.failure(ControlMlCondition.INVALID_STATE, "the transfer of '" + chunk.path()
                        + "' in progress belongs to " + transfer.requester);
            }
            if (chunk.offset() != transfer.written) {
                return Outcome.failure(ControlMlCondition.INVALID_STATE, "chunk at offset " + chunk.offset() + ", but "
                        + transfer.written + " bytes of '" + chunk.path() + "' have arrived; chunks go in order");
            }
            return append(target, transfer, chunk, data);
        }
    }

    /** Starts a transfer with its first chunk. Holds {@link #writeLock}. */
    private Outcome<FileChunk> start(Jid requester, Path target, FileChunk chunk, byte[] data) {
        Path partial = ConfinedRoot.partialFor(target);
        try {
            Files.createDirectories(target.getParent());
            Files.deleteIfExists(partial); // a stale one from an interrupted transfer (a link is removed, not followed)
            try (FileChannel channel = FileChannel.open(partial, StandardOpenOption.CREATE_NEW,
                    StandardOpenOption.WRITE)) {
                writeFully(channel, data, 0);
                if (chunk.last()) {
                    channel.force(true);
                }
            }
        } catch (IOException e) {
            deleteQuietly(partial);
            return fault("writing '" + chunk.path() + "' failed", e);
        }
        if (chunk.last()) {
            return complete(target, partial, chunk.path());
        }
        if (transfers.size() >= limits.maxOpenTransfers()) {
            Iterator<Map.Entry<Path, Transfer>> eldest = transfers.entrySet().iterator();
            Transfer abandoned = eldest.next().getValue();
            eldest.remove();
            deleteQuietly(abandoned.partial);
            LOGGER.info("remote FS: abandoned the transfer to {} of {} ({} bytes): more than {} in progress",
                    abandoned.partial, abandoned.requester, abandoned.written, limits.maxOpenTransfers());
        }
        transfers.put(target, new Transfer(requester, partial, data.length));
        return Outcome.done();
    }

    /** Appends a chunk to a transfer in progress. Holds {@link #writeLock}. */
    private Outcome<FileChunk> append(Path target, Transfer transfer, FileChunk chunk, byte[] data) {
        try (FileChannel channel = FileChannel.open(transfer.partial, StandardOpenOption.WRITE,
                LinkOption.NOFOLLOW_LINKS)) {
            if (channel.size() != transfer.written) {
                transfers.remove(target);
                return Outcome.failure(ControlMlCondition.INVALID_STATE, "the temporary file of '" + chunk.path()
                        + "' changed on the robot; start the transfer again at offset 0");
            }
            try {
                writeFully(channel, data, transfer.written);
                if (chunk.last()) {
                    channel.force(true);
                }
            } catch (IOException e) {
                channel.truncate(transfer.written); // the transfer stays where it was
                throw e;
            }
        } catch (NoSuchFileException e) {
            transfers.remove(target);
            return Outcome.failure(ControlMlCondition.INVALID_STATE, "the temporary file of '" + chunk.path()
                    + "' vanished on the robot; start the transfer again at offset 0");
        } catch (IOException e) {
            return fault("writing '" + chunk.path() + "' failed", e);
        }
        transfer.written += data.length;
        if (chunk.last()) {
            transfers.remove(target);
            return complete(target, transfer.partial, chunk.path());
        }
        return Outcome.done();
    }

    /** Moves a complete temporary file over its target. Holds {@link #writeLock}. */
    private Outcome<FileChunk> complete(Path target, Path partial, String path) {
        try {
            // rename(2) in one directory: readers see the old file or the new one, never a mix
            Files.move(partial, target, StandardCopyOption.ATOMIC_MOVE, StandardCopyOption.REPLACE_EXISTING);
        } catch (IOException e) {
            deleteQuietly(partial);
            return fault("moving '" + path + "' into place failed", e);
        }
        LOGGER.debug("remote FS: wrote {}", target);
        return Outcome.done();
    }

    private static void writeFully(FileChannel channel, byte[] data, long position) throws IOException {
        ByteBuffer buffer = ByteBuffer.wrap(data);
        while (buffer.hasRemaining()) {
            channel.write(buffer, position + buffer.position());
        }
    }

    // ---------------------------------------------------------------------------------------------- delete

    /**
     * {@code cm.fs.delete}: removes a file or an empty directory (a link is removed, not what it points to). The root
     * cannot be deleted.
     *
     * @return {@link Outcome#done()} or why not
     */
    public Outcome<FileQuery> delete(FileQuery query) {
        if (limits.readOnly()) {
            return Outcome.failure(ControlMlCondition.SET_NOT_PERMITTED, "the remote FS of this robot is read-only");
        }
        Path entry;
        try {
            entry = root.entry(query.path());
        } catch (PathRefusal e) {
            return refused(e);
        }
        synchronized (writeLock) {
            try {
                Files.delete(entry);
            } catch (DirectoryNotEmptyException e) {
                return Outcome.failure(ControlMlCondition.INVALID_STATE, "directory '" + query.path()
                        + "' is not empty (temporary files of transfers in progress count)");
            } catch (NoSuchFileException e) {
                return notFound("no file or directory '" + query.path() + "'");
            } catch (IOException e) {
                return fault("deleting '" + query.path() + "' failed", e);
            }
        }
        return Outcome.done();
    }

    // ---------------------------------------------------------------------------------------------- errors

    /** The ControlML error of each path refusal (the table in docs/CONTROLML.md, "Remote FS service"). */
    static ControlMlError errorOf(PathRefusal refusal) {
        return switch (refusal.reason()) {
            case MALFORMED, NOT_A_DIRECTORY -> ControlMlError.of(ControlMlCondition.INVALID_VALUE, refusal
                    .getMessage());
            case OUTSIDE_ROOT -> ControlMlError.of(ControlMlCondition.ACCESS_DENIED, refusal.getMessage());
            case NOT_FOUND -> notFoundError(refusal.getMessage());
        };
    }

    private static <T> Outcome<T> refused(PathRefusal refusal) {
        return Outcome.failure(errorOf(refusal));
    }

    private static ControlMlError notFoundError(String text) {
        // the path is a value that names nothing: item-not-found, with invalid-value as ControlML's reason
        return new ControlMlError(StanzaError.Condition.item_not_found, ControlMlCondition.INVALID_VALUE, text);
    }

    private static <T> Outcome<T> notFound(String text) {
        return Outcome.failure(notFoundError(text));
    }

    private static <T> Outcome<T> fault(String what, Exception e) {
        LOGGER.warn("remote FS: {}", what, e);
        return Outcome.failure(ControlMlCondition.DEVICE_FAULT, what + " (" + e.getClass().getSimpleName() + ")");
    }

    private static void deleteQuietly(Path path) {
        try {
            Files.deleteIfExists(path);
        } catch (IOException e) {
            LOGGER.warn("remote FS: could not delete {}", path, e);
        }
    }
}
