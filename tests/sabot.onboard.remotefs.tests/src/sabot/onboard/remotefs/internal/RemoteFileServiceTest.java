package sabot.onboard.remotefs.internal;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static sabot.testsupport.xmpp.ControlMlAsserts.assertRefused;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Random;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.TimeUnit;
import java.util.stream.Stream;

import org.jivesoftware.smack.packet.StanzaError.Condition;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.payload.DirectoryListing;
import sabot.controlml.payload.FileChunk;
import sabot.controlml.payload.FileEntry;
import sabot.controlml.payload.FileQuery;
import sabot.controlml.swe.SweXml;

/**
 * The service's rules called directly, without a server: the checks the protocol's codec already makes on the wire
 * (checksum), limits set below the protocol's, transfers of several requesters, and thread safety.
 */
class RemoteFileServiceTest {

    @TempDir
    Path root;

    static final Jid WB = jid("wb@sabot.local/workbench");
    static final Jid OTHER_WB = jid("other@sabot.local/workbench");

    static Jid jid(String s) {
        try {
            return JidCreate.from(s);
        } catch (Exception e) {
            throw new IllegalArgumentException(s, e);
        }
    }

    static FileChunk chunk(String path, long offset, byte[] data, boolean last) {
        return new FileChunk(path, offset, data, FileChunk.sha256Hex(data), last);
    }

    static byte[] seeded(int size, long seed) {
        byte[] b = new byte[size];
        new Random(seed).nextBytes(b);
        return b;
    }

    static List<String> namesIn(Path dir) throws Exception {
        try (Stream<Path> s = Files.list(dir)) {
            return s.map(p -> p.getFileName().toString()).sorted().toList();
        }
    }

    @Test
    void chunkWhoseChecksumDoesNotMatchIsRefusedAndNothingIsWritten() throws Exception {
        RemoteFileService fs = new RemoteFileService(root, RemoteFsLimits.DEFAULT);
        byte[] data = seeded(100, 1);
        FileChunk bad = new FileChunk("a.bin", 0, data, FileChunk.sha256Hex(new byte[] { 1 }), true);
        assertRefused(fs.write(WB, bad), Condition.not_acceptable, ControlMlCondition.INVALID_VALUE);
        assertEquals(List.of(), namesIn(root));
    }

    @Test
    void chunkOverTheRobotsLimitIsRefused() throws Exception {
        RemoteFileService fs = new RemoteFileService(root, new RemoteFsLimits(1024, 1 << 20, 16, 4, false));
        assertRefused(fs.write(WB, chunk("a.bin", 0, seeded(1025, 2), true)), Condition.not_acceptable,
                ControlMlCondition.PAYLOAD_TOO_LARGE);
        assertEquals(List.of(), namesIn(root));
        assertTrue(fs.write(WB, chunk("a.bin", 0, seeded(1024, 2), true)).isSuccess());
        assertEquals(1024, Files.size(root.resolve("a.bin")));
    }

    @Test
    void fileOverTheSizeLimitIsRefusedAndTheTransferCanStillFinishWithinIt() throws Exception {
        RemoteFileService fs = new RemoteFileService(root, RemoteFsLimits.DEFAULT.withMaxFileSize(100));
        byte[] data = seeded(100, 3);
        assertTrue(fs.write(WB, chunk("a.bin", 0, Arrays.copyOfRange(data, 0, 64), false)).isSuccess());
        assertRefused(fs.write(WB, chunk("a.bin", 64, seeded(64, 4), true)), Condition.not_acceptable,
                ControlMlCondition.PAYLOAD_TOO_LARGE);
        assertFalse(Files.exists(root.resolve("a.bin")));
        assertTrue(fs.write(WB, chunk("a.bin", 64, Arrays.copyOfRange(data, 64, 100), true)).isSuccess());
        assertArrayEquals(data, Files.readAllBytes(root.resolve("a.bin")));
    }

    @Test
    void aTransferBelongsToTheRequesterWhoStartedIt() throws Exception {
        RemoteFileService fs = new RemoteFileService(root, RemoteFsLimits.DEFAULT);
        byte[] data = seeded(20, 5);
        assertTrue(fs.write(WB, chunk("a.bin", 0, Arrays.copyOfRange(data, 0, 10), false)).isSuccess());
        assertRefused(fs.write(OTHER_WB, chunk("a.bin", 10, Arrays.copyOfRange(data, 10, 20), true)),
                Condition.unexpected_request, ControlMlCondition.INVALID_STATE);
        assertFalse(Files.exists(root.resolve("a.bin")));
        assertTrue(fs.write(WB, chunk("a.bin", 10, Arrays.copyOfRange(data, 10, 20), true)).isSuccess());
        assertArrayEquals(data, Files.readAllBytes(root.resolve("a.bin")));
        assertEquals(0, fs.transfersInProgress());
    }

    @Test
    void theLongestWaitingTransferIsAbandonedWhenTooManyAreOpen() throws Exception {
        RemoteFileService fs = new RemoteFileService(root, new RemoteFsLimits(1024, 1 << 20, 16, 2, false));
        for (String name : List.of("a", "b", "c")) {
            assertTrue(fs.write(WB, chunk(name, 0, new byte[] { 1 }, false)).isSuccess());
        }
        assertEquals(2, fs.transfersInProgress());
        assertEquals(List.of(".b.sabot-partial", ".c.sabot-partial"), namesIn(root), "a's temporary file is gone");
        assertRefused(fs.write(WB, chunk("a", 1, new byte[] { 2 }, true)), Condition.unexpected_request,
                ControlMlCondition.INVALID_STATE);
        assertTrue(fs.write(WB, chunk("b", 1, new byte[] { 2 }, true)).isSuccess());
        assertArrayEquals(new byte[] { 1, 2 }, Files.readAllBytes(root.resolve("b")));
    }

    @Test
    void concurrentWritersAndReadersFromManyThreadsEachGetTheirFile() throws Exception {
        RemoteFileService fs = new RemoteFileService(root, RemoteFsLimits.DEFAULT);
        int writers = 8;
        int size = 100 * 1024;
        int chunk = 4096;
        Files.write(root.resolve("shared.bin"), seeded(size, 99));
        CountDownLatch go = new CountDownLatch(1);
        ExecutorService pool = Executors.newFixedThreadPool(writers * 2);
        List<Future<String>> results = new ArrayList<>();
        for (int w = 0; w < writers; w++) {
            Jid requester = jid("wb" + w + "@sabot.local/workbench");
            String path = "dir" + (w % 2) + "/file" + w + ".bin";
            byte[] data = seeded(size, w);
            results.add(pool.submit(() -> {
                go.await();
                for (int off = 0; off < size; off += chunk) {
                    int n = Math.min(chunk, size - off);
                    Outcome<FileChunk> o = fs.write(requester, chunk(path, off, Arrays.copyOfRange(data, off, off
                            + n), off + n == size));
                    if (!o.isSuccess()) {
                        return path + " at " + off + ": " + o;
                    }
                }
                return null;
            }));
            results.add(pool.submit(() -> {
                go.await();
                byte[] expected = seeded(size, 99);
                for (int off = 0; off < size; off += chunk) {
                    Outcome<FileChunk> o = fs.read(new FileQuery("shared.bin", off, chunk));
                    if (!o.isSuccess() || !Arrays.equals(Arrays.copyOfRange(expected, off, off + chunk), o
                            .orElseThrow().data())) {
                        return "reading shared.bin at " + off + ": " + o;
                    }
                }
                return null;
            }));
        }
        go.countDown();
        pool.shutdown();
        assertTrue(pool.awaitTermination(60, TimeUnit.SECONDS));
        for (Future<String> f : results) {
            assertEquals(null, f.get());
        }
        for (int w = 0; w < writers; w++) {
            assertArrayEquals(seeded(size, w), Files.readAllBytes(root.resolve("dir" + (w % 2) + "/file" + w
                    + ".bin")));
        }
        assertEquals(0, fs.transfersInProgress());
        assertEquals(List.of("file0.bin", "file2.bin", "file4.bin", "file6.bin"), namesIn(root.resolve("dir0")));
    }

    @Test
    void listingPagesFitOnePayloadEvenWithLongNamesFullOfEscapedCharacters() throws Exception {
        RemoteFileService fs = new RemoteFileService(root, RemoteFsLimits.DEFAULT);
        List<String> names = new ArrayList<>();
        for (int i = 0; i < 300; i++) {
            String name = String.format("%03d", i) + "&<>'\"".repeat(47);
            names.add(name);
            Files.writeString(root.resolve(name), "x");
        }
        List<String> seen = new ArrayList<>();
        int pages = 0;
        for (long offset = 0;; pages++) {
            DirectoryListing page = fs.list(new FileQuery("", offset, 0)).orElseThrow();
            if (page.entries().isEmpty()) {
                break;
            }
            StringBuilder xml = new StringBuilder();
            SweXml.write(Resources.FS_LIST.codec().encode(page), xml);
            assertTrue(xml.length() <= RemoteFileService.PAGE_BUDGET, () -> "page of " + xml.length() + " chars");
            page.entries().forEach(e -> seen.add(e.name()));
            offset += page.entries().size();
        }
        assertEquals(names, seen, "every entry once, in order");
        assertTrue(pages > 1, "names this long need several pages");
    }

    @Test
    void namesOfAHundredPlainCharactersFillTheDefaultPage() throws Exception {
        RemoteFileService fs = new RemoteFileService(root, RemoteFsLimits.DEFAULT);
        String padding = "x".repeat(96);
        for (int i = 0; i < 300; i++) {
            Files.writeString(root.resolve(String.format("f%03d", i) + padding), "x".repeat(i));
        }
        List<FileEntry> page = fs.list(new FileQuery("", 10, 0)).orElseThrow().entries();
        assertEquals(RemoteFsLimits.DEFAULT.maxListPage(), page.size());
        assertEquals(new FileEntry("f010" + padding, 10, false), page.get(0));
        assertEquals(List.of(new FileEntry("f299" + padding, 299, false)), fs.list(new FileQuery("", 299, 5))
                .orElseThrow().entries());
    }
}
