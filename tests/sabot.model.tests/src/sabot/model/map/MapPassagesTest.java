package sabot.model.map;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/** Narrow passages of a map: the {@code sabot_passages} key of the map YAML (docs/PASSAGES.md). */
class MapPassagesTest {

    @TempDir
    Path dir;

    private Path yaml(String extra) throws IOException {
        Path p = dir.resolve("map.yaml");
        Files.writeString(p, "image: map.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
                + "occupied_thresh: 0.65\nfree_thresh: 0.196\n" + extra, StandardCharsets.UTF_8);
        return p;
    }

    @Test
    void passagesAreNumberedFromOneInTheYamlsOrder() throws IOException {
        assertEquals(List.of(new Passage(1, 4.2, 1.7, 4.4, 2.7), new Passage(2, -1, 0, 1, 0.5)), MapServerFormat
                .readPassages(yaml("sabot_passages: [[4.2, 1.7, 4.4, 2.7], [ -1,0 ,1, 5e-1]]  # a door, a gap\n")));
        assertEquals(List.of(), MapServerFormat.readPassages(yaml("sabot_passages: []\n")));
        assertEquals(List.of(), MapServerFormat.readPassages(yaml("")), "no key, no passages");
    }

    @Test
    void theTwoRoomsMapHasItsDoor() throws IOException {
        Path map = null;
        for (Path d = Path.of("").toAbsolutePath(); d != null && map == null; d = d.getParent()) {
            Path candidate = d.resolve("onboard-bridge/maps/two-rooms.yaml");
            map = Files.isRegularFile(candidate) ? candidate : null;
        }
        assertTrue(map != null, "no onboard-bridge/maps/two-rooms.yaml above " + Path.of("").toAbsolutePath());
        assertEquals(List.of(new Passage(1, 4.2, 1.7, 4.4, 2.7)), MapServerFormat.readPassages(map));
    }

    @Test
    void aBadPassagesListNamesTheFileAndTheKey() throws IOException {
        for (String bad : List.of("", "[", "[[1, 2, 3, 4]", "[[1, 2]]", "[[1, 2, 3, 4, 5]]", "[[a, 2, 3, 4]]",
                "[1, 2, 3, 4]", "[[1, 2, 3, 4]] x", "[[1, 2, 3, 4],]")) {
            Path y = yaml("sabot_passages: " + bad + "\n");
            MapFormatException e = assertThrows(MapFormatException.class, () -> MapServerFormat.readPassages(y), bad);
            assertTrue(e.getMessage().contains("map.yaml") && e.getMessage().contains("key 'sabot_passages' is '"
                    + bad.strip() + "', expected [[minX, minY, maxX, maxY], ...] (numbers, metres)"), e.getMessage());
        }
        Path flipped = yaml("sabot_passages: [[4.4, 1.7, 4.2, 2.7]]\n");
        assertTrue(assertThrows(MapFormatException.class, () -> MapServerFormat.readPassages(flipped)).getMessage()
                .contains("passage 1 [4.4, 1.7, 4.2, 2.7] is not a rectangle"));
    }

    @Test
    void aFootprintTouchesAPassageWhenItOverlapsTheRectangle() {
        Passage door = new Passage(1, 4.2, 1.7, 4.4, 2.7);
        assertTrue(door.touches(4.3, 2.2, 0.25), "inside");
        assertTrue(door.touches(4.0, 2.2, 0.25), "0.2 m west of it");
        assertFalse(door.touches(3.9, 2.2, 0.25), "0.3 m west of it");
        assertEquals(Math.hypot(0.3, 0.4), door.distance(4.7, 3.1), 1e-12, "from the corner");
        assertThrows(IllegalArgumentException.class, () -> new Passage(0, 0, 0, 1, 1));
    }
}
