package sabot.model.map;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import sabot.model.geometry.Point2D;

/**
 * Charging docks of a map: the {@code sabot_docks} key of the map YAML, as the simulator's world loader
 * (onboard-bridge/sim/world.c, world_parse_docks) reads it too.
 */
class MapDocksTest {

    @TempDir
    Path dir;

    private Path yaml(String extra) throws IOException {
        Path p = dir.resolve("map.yaml");
        Files.writeString(p, "image: map.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
                + "occupied_thresh: 0.65\nfree_thresh: 0.196\n" + extra, StandardCharsets.UTF_8);
        return p;
    }

    @Test
    void docksAreReadInTheYamlsOrder() throws IOException {
        assertEquals(List.of(new Point2D(1.0, 1.0), new Point2D(11.0, 1.0)), MapServerFormat.readDocks(yaml(
                "sabot_docks: [[1.0, 1.0], [11.0, 1.0]]  # two\n")));
        assertEquals(List.of(new Point2D(-1.5, 0.2)), MapServerFormat.readDocks(yaml("sabot_docks: [ [ -1.5 ,2e-1 ] ]\n")));
        assertEquals(List.of(), MapServerFormat.readDocks(yaml("sabot_docks: []\n")));
        assertEquals(List.of(), MapServerFormat.readDocks(yaml("")), "no key, no docks");
    }

    @Test
    void aBadDocksListNamesTheFileAndTheKey() throws IOException {
        for (String bad : List.of("", "[", "[[1, 2]", "[[1, 2],]", "[[1]]", "[[1, 2, 3]]", "[[a, 2]]", "[[1, NaN]]",
                "[1, 2]", "[[1, 2]] x", "[[1, 2] [3, 4]]", "[[0x10, 1]]")) {
            Path y = yaml("sabot_docks: " + bad + "\n");
            MapFormatException e = assertThrows(MapFormatException.class, () -> MapServerFormat.readDocks(y), bad);
            assertTrue(e.getMessage().contains("map.yaml") && e.getMessage().contains(
                    "key 'sabot_docks' is '" + bad.strip() + "', expected [[x, y], ...] (numbers, metres)"),
                    e.getMessage());
        }
        StringBuilder many = new StringBuilder("[");
        for (int i = 0; i <= MapServerFormat.MAX_DOCKS; i++) {
            many.append(i == 0 ? "" : ", ").append("[").append(i).append(", 1]");
        }
        Path y = yaml("sabot_docks: " + many + "]\n");
        assertTrue(assertThrows(MapFormatException.class, () -> MapServerFormat.readDocks(y)).getMessage().contains(
                "lists 17 docks, at most 16"));
    }
}
