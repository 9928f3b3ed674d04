package sabot.onboard.remotefs.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;

import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import sabot.onboard.remotefs.internal.PathRefusal.Reason;

/** Path confinement without any server: what a requester's path may be, and that it never leaves the root. */
class ConfinedRootTest {

    @TempDir
    Path rootDir;
    @TempDir
    Path outside;

    ConfinedRoot root;

    @BeforeEach
    void tree() throws Exception {
        Files.createDirectories(rootDir.resolve("maps/lab"));
        Files.writeString(rootDir.resolve("maps/lab/floor.pgm"), "P5");
        Files.writeString(rootDir.resolve("notes.txt"), "n");
        Files.writeString(outside.resolve("secret.txt"), "s");
        Files.createSymbolicLink(rootDir.resolve("escape"), outside);
        Files.createSymbolicLink(rootDir.resolve("escape.txt"), outside.resolve("secret.txt"));
        Files.createSymbolicLink(rootDir.resolve("nowhere"), rootDir.resolve("missing"));
        Files.createSymbolicLink(rootDir.resolve("lab"), rootDir.resolve("maps/lab"));
        root = new ConfinedRoot(rootDir);
    }

    @Test
    void plainRelativePathsSplitIntoSegments() throws Exception {
        assertEquals(List.of(), ConfinedRoot.segments(""));
        assertEquals(List.of("maps", "lab", "floor.pgm"), ConfinedRoot.segments("maps/lab/floor.pgm"));
        assertEquals(List.of(".hidden", "a..b", "x y"), ConfinedRoot.segments(".hidden/a..b/x y"));
    }

    @ParameterizedTest
    @ValueSource(strings = { "../x", "..", "a/../../x", "a/..", "/etc/passwd", "/", "a//b", "a/", "a/./b", ".",
        "a\\b", "..\\x", "a\u0000b", "a\nb", "a\u007fb", ".floor.pgm.sabot-partial", "maps/.x.sabot-partial" })
    void malformedPathsAreRefused(String path) {
        PathRefusal e = assertThrows(PathRefusal.class, () -> ConfinedRoot.segments(path));
        assertEquals(Reason.MALFORMED, e.reason());
        PathRefusal viaRoot = assertThrows(PathRefusal.class, () -> root.forWrite(path));
        assertEquals(Reason.MALFORMED, viaRoot.reason());
    }

    @Test
    void overlongSegmentsAndPathsAreRefused() throws Exception {
        String segment = "s".repeat(ConfinedRoot.MAX_SEGMENT);
        assertEquals(List.of(segment), ConfinedRoot.segments(segment));
        assertEquals(Reason.MALFORMED, assertThrows(PathRefusal.class, () -> ConfinedRoot.segments(segment + "s"))
                .reason());
        String path = ("a/").repeat(ConfinedRoot.MAX_PATH / 2) + "b";
        assertEquals(Reason.MALFORMED, assertThrows(PathRefusal.class, () -> ConfinedRoot.segments(path)).reason());
    }

    @Test
    void existingPathsResolveInsideTheRoot() throws Exception {
        assertEquals(root.root(), root.existing(""));
        assertEquals(root.root().resolve("maps/lab/floor.pgm"), root.existing("maps/lab/floor.pgm"));
        assertEquals(root.root().resolve("maps/lab/floor.pgm"), root.existing("lab/floor.pgm"),
                "a link inside the root is followed");
    }

    @ParameterizedTest
    @ValueSource(strings = { "escape", "escape/secret.txt", "escape.txt", "nowhere" })
    void linksLeadingOutOfTheRootOrNowhereAreRefused(String path) {
        assertEquals(Reason.OUTSIDE_ROOT, assertThrows(PathRefusal.class, () -> root.existing(path)).reason());
        assertEquals(Reason.OUTSIDE_ROOT, assertThrows(PathRefusal.class, () -> root.entry(path)).reason());
        assertEquals(Reason.OUTSIDE_ROOT, assertThrows(PathRefusal.class, () -> root.forWrite(path)).reason());
    }

    @Test
    void writesThroughALinkOutOfTheRootAreRefusedEvenToNewNames() {
        assertEquals(Reason.OUTSIDE_ROOT, assertThrows(PathRefusal.class, () -> root.forWrite("escape/new.txt"))
                .reason());
        assertEquals(Reason.OUTSIDE_ROOT, assertThrows(PathRefusal.class, () -> root.forWrite("escape/a/b/c.txt"))
                .reason());
        assertFalse(Files.exists(outside.resolve("new.txt")));
        assertFalse(Files.exists(outside.resolve("a")));
    }

    @Test
    void missingPathsAreNotFoundAndFilesAreNoDirectories() {
        assertEquals(Reason.NOT_FOUND, assertThrows(PathRefusal.class, () -> root.existing("maps/none.pgm"))
                .reason());
        assertEquals(Reason.NOT_FOUND, assertThrows(PathRefusal.class, () -> root.entry("none/x")).reason());
        assertEquals(Reason.NOT_A_DIRECTORY, assertThrows(PathRefusal.class, () -> root.existing("notes.txt/x"))
                .reason());
        assertEquals(Reason.NOT_A_DIRECTORY, assertThrows(PathRefusal.class, () -> root.forWrite("notes.txt/x"))
                .reason());
    }

    @Test
    void theRootItselfCannotBeDeletedOrWritten() {
        assertEquals(Reason.MALFORMED, assertThrows(PathRefusal.class, () -> root.entry("")).reason());
        assertEquals(Reason.MALFORMED, assertThrows(PathRefusal.class, () -> root.forWrite("")).reason());
    }

    @Test
    void writeTargetsMayBeNewUnderNewDirectoriesAndNothingIsCreated() throws Exception {
        assertEquals(root.root().resolve("new/dir/file.bin"), root.forWrite("new/dir/file.bin"));
        assertEquals(root.root().resolve("maps/lab/floor.pgm"), root.forWrite("lab/floor.pgm"));
        assertFalse(Files.exists(rootDir.resolve("new")));
    }

    @Test
    void entryOfALinkIsTheLinkItself() throws Exception {
        assertEquals(root.root().resolve("lab"), root.entry("lab"));
        assertTrue(Files.isSymbolicLink(root.entry("lab")));
    }

    @Test
    void partialFileIsAHiddenSiblingWithAReservedName() {
        Path partial = ConfinedRoot.partialFor(rootDir.resolve("maps/big.bin"));
        assertEquals(rootDir.resolve("maps/.big.bin.sabot-partial"), partial);
        assertTrue(ConfinedRoot.isPartialName(partial.getFileName().toString()));
        assertFalse(ConfinedRoot.isPartialName("big.bin"));
        assertFalse(ConfinedRoot.isPartialName(".sabot-partial"));
    }
}
