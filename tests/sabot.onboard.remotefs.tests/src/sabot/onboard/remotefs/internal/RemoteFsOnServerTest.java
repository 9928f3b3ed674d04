package sabot.onboard.remotefs.internal;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static sabot.testsupport.xmpp.ControlMlAsserts.assertRefused;

import java.io.ByteArrayOutputStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.LinkOption;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Random;
import java.util.TreeMap;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.stream.Stream;

import org.jivesoftware.smack.packet.StanzaError.Condition;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.Arguments;
import org.junit.jupiter.params.provider.MethodSource;
import org.jxmpp.jid.Jid;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.payload.DirectoryListing;
import sabot.controlml.payload.FileChunk;
import sabot.controlml.payload.FileEntry;
import sabot.controlml.payload.FileQuery;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * The remote FS between a robot connection (serving) and a workbench connection (requesting) through a real private
 * server (the same suite on Prosody and on ejabberd): round trips, paging, deletes, and every bad input refused with
 * its condition, the disk unchanged and the connection still serving.
 */
abstract class RemoteFsOnServerTest {

    /** @return the running private server of the concrete class (Prosody or ejabberd) */
    protected abstract PrivateXmppServer server();

    private static final AtomicInteger ACCOUNTS = new AtomicInteger();

    @TempDir
    Path root;
    @TempDir
    Path outside;

    ControlMlManager robotManager;
    Jid robot;
    ControlMlManager workbench;

    @BeforeEach
    void robotAndWorkbench() throws Exception {
        int n = ACCOUNTS.incrementAndGet();
        XMPPTCPConnection wb = server().login("fs-wb-" + n);
        XMPPTCPConnection robotConnection = server().login("fs-robot-" + n);
        robotManager = ControlMlManager.getInstanceFor(robotConnection);
        Jid allowed = wb.getUser().asBareJid();
        robotManager.setAccessPolicy(j -> j.asBareJid().equals(allowed) ? Role.MAINTAINER : Role.NONE);
        robot = robotConnection.getUser();
        workbench = ControlMlManager.getInstanceFor(wb);
    }

    RemoteFileService serve(RemoteFsLimits limits) throws Exception {
        RemoteFileService fs = new RemoteFileService(root, limits);
        fs.register(robotManager);
        return fs;
    }

    // ------------------------------------------------------------------------------------------------ helpers

    static byte[] seeded(int size, long seed) {
        byte[] b = new byte[size];
        new Random(seed).nextBytes(b);
        return b;
    }

    static FileChunk chunk(String path, long offset, byte[] data, boolean last) {
        return new FileChunk(path, offset, data, FileChunk.sha256Hex(data), last);
    }

    Outcome<FileChunk> write(FileChunk chunk) {
        return workbench.set(robot, Resources.FS_WRITE, chunk);
    }

    void upload(String path, byte[] content, int chunkSize) {
        int offset = 0;
        do {
            int n = Math.min(chunkSize, content.length - offset);
            Outcome<FileChunk> o = write(chunk(path, offset, Arrays.copyOfRange(content, offset, offset + n), offset
                    + n == content.length));
            assertTrue(o.isSuccess(), () -> "chunk of " + path + ": " + o);
            offset += n;
        } while (offset < content.length);
    }

    byte[] download(String path, int chunkSize) {
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        for (int chunks = 0;; chunks++) {
            assertTrue(chunks < 10_000, "a download ends");
            FileChunk c = workbench.get(robot, Resources.FS_READ, new FileQuery(path, out.size(), chunkSize))
                    .orElseThrow();
            assertEquals(out.size(), c.offset());
            out.writeBytes(c.data());
            if (c.last()) {
                return out.toByteArray();
            }
        }
    }

    List<FileEntry> list(String path, long offset, long length) {
        return workbench.get(robot, Resources.FS_LIST, new FileQuery(path, offset, length)).orElseThrow().entries();
    }

    /** Every entry under a directory, links not followed: name → content hash, "dir" or the link's target. */
    static TreeMap<String, String> snapshot(Path dir) throws Exception {
        TreeMap<String, String> s = new TreeMap<>();
        try (Stream<Path> all = Files.walk(dir)) {
            for (Path p : (Iterable<Path>) all::iterator) {
                String key = dir.relativize(p).toString();
                if (Files.isSymbolicLink(p)) {
                    s.put(key, "link to " + Files.readSymbolicLink(p));
                } else if (Files.isDirectory(p, LinkOption.NOFOLLOW_LINKS)) {
                    s.put(key, "dir");
                } else {
                    s.put(key, FileChunk.sha256Hex(Files.readAllBytes(p)));
                }
            }
        }
        return s;
    }

    static List<String> namesIn(Path dir) throws Exception {
        try (Stream<Path> s = Files.list(dir)) {
            return s.map(p -> p.getFileName().toString()).sorted().toList();
        }
    }

    // ------------------------------------------------------------------------------------------------ tests

    @Test
    void multiChunkFileWrittenThenReadBackIdentical() throws Exception {
        serve(RemoteFsLimits.DEFAULT);
        byte[] content = seeded(100 * 1024, 20261121L);

        upload("maps/lab/big.bin", content, FileChunk.MAX_CHUNK); // 4 chunks, the last 4 KiB

        assertArrayEquals(content, Files.readAllBytes(root.resolve("maps/lab/big.bin")));
        assertEquals(List.of("big.bin"), namesIn(root.resolve("maps/lab")), "no temporary file is left");
        assertArrayEquals(content, download("maps/lab/big.bin", FileChunk.MAX_CHUNK));
        assertArrayEquals(content, download("maps/lab/big.bin", 10_000), "any chunking reads the same bytes");
        assertArrayEquals(content, download("maps/lab/big.bin", 0), "length 0 reads whole chunks");

        FileChunk tail = workbench.get(robot, Resources.FS_READ, new FileQuery("maps/lab/big.bin", content.length
                - 5, 100)).orElseThrow();
        assertArrayEquals(Arrays.copyOfRange(content, content.length - 5, content.length), tail.data());
        assertTrue(tail.last());
    }

    @Test
    void workbenchesOnTwoRobotConnectionsUploadAtOnceAndEachGetsItsFile() throws Exception {
        RemoteFileService fs = serve(RemoteFsLimits.DEFAULT);
        // a second connection of the same robot, served by the same service: its handlers run on another thread
        int n = ACCOUNTS.incrementAndGet();
        XMPPTCPConnection otherWb = server().login("fs-wb-" + n);
        XMPPTCPConnection otherRobotConnection = server().login("fs-robot-" + n);
        ControlMlManager otherRobot = ControlMlManager.getInstanceFor(otherRobotConnection);
        otherRobot.setAccessPolicy(j -> j.asBareJid().equals(otherWb.getUser().asBareJid()) ? Role.MAINTAINER
                : Role.NONE);
        fs.register(otherRobot);
        ControlMlManager other = ControlMlManager.getInstanceFor(otherWb);
        Jid otherRobotJid = otherRobotConnection.getUser();

        byte[] mine = seeded(200 * 1024, 1);
        byte[] theirs = seeded(200 * 1024, 2);
        ExecutorService pool = Executors.newFixedThreadPool(2);
        try {
            Future<?> a = pool.submit(() -> upload("shared/mine.bin", mine, 8192));
            Future<?> b = pool.submit(() -> {
                for (int off = 0; off < theirs.length; off += 8192) {
                    byte[] part = Arrays.copyOfRange(theirs, off, off + 8192);
                    Outcome<FileChunk> o = other.set(otherRobotJid, Resources.FS_WRITE, chunk("shared/theirs.bin",
                            off, part, off + 8192 == theirs.length));
                    assertTrue(o.isSuccess(), o::toString);
                }
            });
            a.get();
            b.get();
        } finally {
            pool.shutdown();
        }
        assertArrayEquals(mine, Files.readAllBytes(root.resolve("shared/mine.bin")));
        assertArrayEquals(theirs, Files.readAllBytes(root.resolve("shared/theirs.bin")));
        assertEquals(List.of("mine.bin", "theirs.bin"), namesIn(root.resolve("shared")));
        assertEquals(0, fs.transfersInProgress());

        // a transfer belongs to its requester: the other workbench cannot continue mine
        assertTrue(write(chunk("shared/next.bin", 0, new byte[] { 1 }, false)).isSuccess());
        assertRefused(other.set(otherRobotJid, Resources.FS_WRITE, chunk("shared/next.bin", 1, new byte[] { 2 },
                true)), Condition.unexpected_request, ControlMlCondition.INVALID_STATE);
        assertFalse(Files.exists(root.resolve("shared/next.bin")));
    }

    @Test
    void writingAnExistingFileReplacesItWhole() throws Exception {
        serve(RemoteFsLimits.DEFAULT);
        Files.write(root.resolve("config.yaml"), seeded(50_000, 1));
        byte[] shorter = "resolution: 0.05\n".getBytes(StandardCharsets.UTF_8);
        upload("config.yaml", shorter, 8);
        assertArrayEquals(shorter, download("config.yaml", 0));
        upload("empty", new byte[0], 8);
        assertEquals(0, Files.size(root.resolve("empty")));
        assertArrayEquals(new byte[0], download("empty", 0));
    }

    @Test
    void listingIsSortedByNameAndPaged() throws Exception {
        serve(RemoteFsLimits.DEFAULT);
        Files.writeString(root.resolve("charlie.txt"), "ccc");
        Files.writeString(root.resolve("alpha.txt"), "a");
        Files.createDirectories(root.resolve("delta/inner"));
        Files.writeString(root.resolve("bravo.bin"), "bb");
        Files.writeString(root.resolve("echo"), "");
        Files.writeString(root.resolve(".echo.sabot-partial"), "a transfer in progress is not listed");
        Files.createSymbolicLink(root.resolve("foxtrot"), outside);

        List<FileEntry> all = List.of(new FileEntry("alpha.txt", 1, false), new FileEntry("bravo.bin", 2, false),
                new FileEntry("charlie.txt", 3, false), new FileEntry("delta", 0, true), new FileEntry("echo", 0,
                        false));
        assertEquals(all, list("", 0, 0));
        assertEquals(all.subList(0, 2), list("", 0, 2));
        assertEquals(all.subList(2, 4), list("", 2, 2));
        assertEquals(all.subList(4, 5), list("", 4, 2));
        assertEquals(List.of(), list("", 5, 2));
        assertEquals(List.of(), list("", 1000, 0));
        assertEquals(List.of(new FileEntry("inner", 0, true)), list("delta", 0, 0));
        assertEquals(List.of(), list("delta/inner", 0, 0));
        DirectoryListing answer = workbench.get(robot, Resources.FS_LIST, new FileQuery("delta", 0, 0))
                .orElseThrow();
        assertEquals("delta", answer.path());
    }

    @Test
    void aPageOfLongNamesFullOfEscapedCharactersCrossesTheServer() throws Exception {
        serve(RemoteFsLimits.DEFAULT);
        List<String> names = new ArrayList<>();
        for (int i = 0; i < 100; i++) {
            names.add(String.format("%03d", i) + "&<>'\"".repeat(47));
            Files.writeString(root.resolve(names.get(i)), "x");
        }
        List<String> seen = new ArrayList<>();
        List<FileEntry> page;
        while (!(page = list("", seen.size(), 0)).isEmpty()) {
            page.forEach(e -> seen.add(e.name()));
        }
        assertEquals(names, seen);
    }

    @Test
    void deleteRemovesAFileAndAnEmptyDirectory() throws Exception {
        serve(RemoteFsLimits.DEFAULT);
        Files.createDirectories(root.resolve("logs/old"));
        Files.writeString(root.resolve("logs/run1.log"), "x");
        Files.createSymbolicLink(root.resolve("latest"), root.resolve("logs/run1.log"));

        assertTrue(workbench.set(robot, Resources.FS_DELETE, new FileQuery("latest", 0, 0)).isSuccess());
        assertFalse(Files.exists(root.resolve("latest"), LinkOption.NOFOLLOW_LINKS));
        assertTrue(Files.exists(root.resolve("logs/run1.log")), "a link is removed, not what it points to");
        assertTrue(workbench.set(robot, Resources.FS_DELETE, new FileQuery("logs/run1.log", 0, 0)).isSuccess());
        assertTrue(workbench.set(robot, Resources.FS_DELETE, new FileQuery("logs/old", 0, 0)).isSuccess());
        assertTrue(workbench.set(robot, Resources.FS_DELETE, new FileQuery("logs", 0, 0)).isSuccess());
        assertEquals(List.of(), namesIn(root));
        assertEquals(List.of(), list("", 0, 0));
    }

    @Test
    void interruptedTransferLeavesNoFileUnderTheTargetNameAndANewOneReplacesItsTemporaryFile() throws Exception {
        serve(RemoteFsLimits.DEFAULT);
        byte[] first = seeded(70_000, 7);
        assertTrue(write(chunk("maps/big.bin", 0, Arrays.copyOfRange(first, 0, 32_768), false)).isSuccess());
        // the workbench goes away here: only the first of three chunks arrived

        assertFalse(Files.exists(root.resolve("maps/big.bin")));
        assertEquals(List.of(), list("maps", 0, 0));
        assertRefused(workbench.get(robot, Resources.FS_READ, new FileQuery("maps/big.bin", 0, 0)),
                Condition.item_not_found, ControlMlCondition.INVALID_VALUE);

        byte[] second = seeded(40_000, 8);
        upload("maps/big.bin", second, 32_768);
        assertArrayEquals(second, Files.readAllBytes(root.resolve("maps/big.bin")));
        assertEquals(List.of("big.bin"), namesIn(root.resolve("maps")), "the stale temporary file is gone");
    }

    @Test
    void staleTemporaryFileOfAnEarlierRunIsReplacedByANewTransfer() throws Exception {
        Files.createDirectories(root.resolve("maps"));
        Files.write(root.resolve("maps/.big.bin.sabot-partial"), seeded(5000, 9)); // left by a robot that crashed
        serve(RemoteFsLimits.DEFAULT);
        assertRefused(write(chunk("maps/big.bin", 5000, new byte[] { 1 }, true)), Condition.unexpected_request,
                ControlMlCondition.INVALID_STATE);
        byte[] content = seeded(3000, 10);
        upload("maps/big.bin", content, 1000);
        assertArrayEquals(content, Files.readAllBytes(root.resolve("maps/big.bin")));
        assertEquals(List.of("big.bin"), namesIn(root.resolve("maps")));
    }

    @Test
    void readOnlyRobotRefusesWritesAndDeletesButServesReads() throws Exception {
        serve(RemoteFsLimits.DEFAULT.asReadOnly());
        Files.writeString(root.resolve("keep.txt"), "keep");
        TreeMap<String, String> before = snapshot(root);

        assertRefused(write(chunk("new.txt", 0, new byte[] { 1 }, true)), Condition.forbidden,
                ControlMlCondition.SET_NOT_PERMITTED);
        assertRefused(write(chunk("keep.txt", 0, new byte[] { 1 }, true)), Condition.forbidden,
                ControlMlCondition.SET_NOT_PERMITTED);
        assertRefused(workbench.set(robot, Resources.FS_DELETE, new FileQuery("keep.txt", 0, 0)),
                Condition.forbidden, ControlMlCondition.SET_NOT_PERMITTED);

        assertEquals(before, snapshot(root));
        assertArrayEquals("keep".getBytes(StandardCharsets.UTF_8), download("keep.txt", 0));
    }

    @Test
    void unregisteredServiceIsNoLongerServed() throws Exception {
        RemoteFileService fs = serve(RemoteFsLimits.DEFAULT);
        assertTrue(workbench.get(robot, Resources.FS_LIST, new FileQuery("", 0, 0)).isSuccess());
        fs.unregister(robotManager);
        assertRefused(workbench.get(robot, Resources.FS_LIST, new FileQuery("", 0, 0)), Condition.service_unavailable,
                ControlMlCondition.UNSUPPORTED_OPERATION);
        assertRefused(write(chunk("a", 0, new byte[] { 1 }, true)), Condition.service_unavailable,
                ControlMlCondition.UNSUPPORTED_OPERATION);
        assertFalse(Files.exists(root.resolve("a")));
    }

    // ------------------------------------------------------------------------------------------------ bad input

    /** One bad request: what is prepared first (valid requests), the request, and the refusal expected. */
    interface BadRequest {
        Outcome<?> send(RemoteFsOnServerTest t);
    }

    interface Preparation {
        void run(RemoteFsOnServerTest t) throws Exception;
    }

    static Arguments bad(String name, Condition condition, ControlMlCondition reason, BadRequest request) {
        return bad(name, t -> {
        }, condition, reason, request);
    }

    static Arguments bad(String name, Preparation preparation, Condition condition, ControlMlCondition reason,
            BadRequest request) {
        return Arguments.of(name, preparation, condition, reason, request);
    }

    static Outcome<FileChunk> read(RemoteFsOnServerTest t, String path) {
        return t.workbench.get(t.robot, Resources.FS_READ, new FileQuery(path, 0, 0));
    }

    static Outcome<FileChunk> writeOne(RemoteFsOnServerTest t, String path) {
        return t.write(chunk(path, 0, "new".getBytes(StandardCharsets.UTF_8), true));
    }

    static Outcome<FileQuery> delete(RemoteFsOnServerTest t, String path) {
        return t.workbench.set(t.robot, Resources.FS_DELETE, new FileQuery(path, 0, 0));
    }

    static final Condition NOT_ACCEPTABLE = Condition.not_acceptable;
    static final ControlMlCondition INVALID = ControlMlCondition.INVALID_VALUE;

    static Stream<Arguments> badRequests() {
        byte[] ten = seeded(10, 11);
        Preparation started = t -> assertTrue(t.write(chunk("upload.bin", 0, ten, false)).isSuccess());
        return Stream.of(
                // refused by the protocol's path rule before the service sees them
                bad("read ../x", NOT_ACCEPTABLE, INVALID, t -> read(t, "../x")),
                bad("write ../keep.txt", NOT_ACCEPTABLE, INVALID, t -> writeOne(t, "../keep.txt")),
                bad("read /etc/passwd", NOT_ACCEPTABLE, INVALID, t -> read(t, "/etc/passwd")),
                bad("write /tmp/x", NOT_ACCEPTABLE, INVALID, t -> writeOne(t, "/tmp/x")),
                bad("read dir//inner.txt", NOT_ACCEPTABLE, INVALID, t -> read(t, "dir//inner.txt")),
                bad("delete dir//inner.txt", NOT_ACCEPTABLE, INVALID, t -> delete(t, "dir//inner.txt")),
                bad("read dir\\inner.txt", NOT_ACCEPTABLE, INVALID, t -> read(t, "dir\\inner.txt")),
                bad("write dir\\new.txt", NOT_ACCEPTABLE, INVALID, t -> writeOne(t, "dir\\new.txt")),
                // refused by the service's own confinement
                bad("write ./keep.txt", NOT_ACCEPTABLE, INVALID, t -> writeOne(t, "./keep.txt")),
                bad("read dir/./inner.txt", NOT_ACCEPTABLE, INVALID, t -> read(t, "dir/./inner.txt")),
                bad("write a reserved temporary-file name", NOT_ACCEPTABLE, INVALID, t -> writeOne(t,
                        ".keep.txt.sabot-partial")),
                bad("read through a link out of the root", Condition.forbidden, ControlMlCondition.ACCESS_DENIED,
                        t -> read(t, "escape/secret.txt")),
                bad("list a link out of the root", Condition.forbidden, ControlMlCondition.ACCESS_DENIED,
                        t -> t.workbench.get(t.robot, Resources.FS_LIST, new FileQuery("escape", 0, 0))),
                bad("write through a link out of the root", Condition.forbidden, ControlMlCondition.ACCESS_DENIED,
                        t -> writeOne(t, "escape/new.txt")),
                bad("write over a link out of the root", Condition.forbidden, ControlMlCondition.ACCESS_DENIED,
                        t -> writeOne(t, "escape.txt")),
                bad("delete through a link out of the root", Condition.forbidden, ControlMlCondition.ACCESS_DENIED,
                        t -> delete(t, "escape/secret.txt")),
                // chunks
                bad("wrong sha256", NOT_ACCEPTABLE, INVALID, t -> t.write(new FileChunk("upload.bin", 0, ten,
                        FileChunk.sha256Hex(new byte[] { 1 }), true))),
                bad("chunk before the transfer started", Condition.unexpected_request,
                        ControlMlCondition.INVALID_STATE, t -> t.write(chunk("upload.bin", 10, ten, true))),
                bad("out-of-order offset", started, Condition.unexpected_request, ControlMlCondition.INVALID_STATE,
                        t -> t.write(chunk("upload.bin", 20, ten, true))),
                bad("offset inside the bytes already written", started, Condition.unexpected_request,
                        ControlMlCondition.INVALID_STATE, t -> t.write(chunk("upload.bin", 5, ten, true))),
                bad("chunk over the limit", started, NOT_ACCEPTABLE, ControlMlCondition.PAYLOAD_TOO_LARGE,
                        t -> t.write(chunk("upload.bin", 10, new byte[FileChunk.MAX_CHUNK + 1],
                                false))),
                bad("write onto a directory", NOT_ACCEPTABLE, INVALID, t -> writeOne(t, "dir")),
                bad("write under a file", NOT_ACCEPTABLE, INVALID, t -> writeOne(t, "keep.txt/new.txt")),
                // missing and wrong kinds
                bad("read a missing file", Condition.item_not_found, INVALID, t -> read(t, "missing.txt")),
                bad("list a missing directory", Condition.item_not_found, INVALID, t -> t.workbench.get(t.robot,
                        Resources.FS_LIST, new FileQuery("missing", 0, 0))),
                bad("delete a missing file", Condition.item_not_found, INVALID, t -> delete(t, "dir/missing.txt")),
                bad("read a directory", NOT_ACCEPTABLE, INVALID, t -> read(t, "dir")),
                bad("list a file", NOT_ACCEPTABLE, INVALID, t -> t.workbench.get(t.robot, Resources.FS_LIST,
                        new FileQuery("keep.txt", 0, 0))),
                bad("read past the end", NOT_ACCEPTABLE, INVALID, t -> t.workbench.get(t.robot, Resources.FS_READ,
                        new FileQuery("keep.txt", 5, 0))),
                bad("delete a non-empty directory", Condition.unexpected_request, ControlMlCondition.INVALID_STATE,
                        t -> delete(t, "dir")),
                bad("delete the root", NOT_ACCEPTABLE, INVALID, t -> delete(t, "")));
    }

    @ParameterizedTest(name = "{0}")
    @MethodSource("badRequests")
    void badRequestIsRefusedLeavesTheDiskUnchangedAndTheConnectionServing(String name, Preparation preparation,
            Condition condition, ControlMlCondition reason, BadRequest request) throws Exception {
        serve(RemoteFsLimits.DEFAULT);
        Files.writeString(root.resolve("keep.txt"), "keep");
        Files.createDirectories(root.resolve("dir"));
        Files.writeString(root.resolve("dir/inner.txt"), "inner");
        Files.writeString(outside.resolve("secret.txt"), "secret");
        Files.createSymbolicLink(root.resolve("escape"), outside);
        Files.createSymbolicLink(root.resolve("escape.txt"), outside.resolve("secret.txt"));
        preparation.run(this);
        TreeMap<String, String> rootBefore = snapshot(root);
        TreeMap<String, String> outsideBefore = snapshot(outside);

        assertRefused(request.send(this), condition, reason);

        assertEquals(rootBefore, snapshot(root), "nothing changed in the root");
        assertEquals(outsideBefore, snapshot(outside), "nothing changed outside the root");
        assertArrayEquals("keep".getBytes(StandardCharsets.UTF_8), download("keep.txt", 0),
                "the connection still serves");
        upload("after.txt", "after".getBytes(StandardCharsets.UTF_8), 2);
        assertEquals("after", Files.readString(root.resolve("after.txt")));
    }
}
