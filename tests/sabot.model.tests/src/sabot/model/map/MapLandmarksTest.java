package sabot.model.map;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

import sabot.model.geometry.Point2D;

/**
 * Ceiling landmarks of a map: the {@code sabot_landmarks} key of the map YAML and the landmarks file it names, the
 * format the simulator's world loader (onboard-bridge/sim/world.c) reads too.
 */
class MapLandmarksTest {

    @TempDir
    Path dir;

    private Path write(String name, String text) throws IOException {
        Path p = dir.resolve(name);
        Files.writeString(p, text, StandardCharsets.UTF_8);
        return p;
    }

    /** A map YAML in {@link #dir} with the given extra lines (the image need not exist: only the YAML is read). */
    private Path yaml(String extra) throws IOException {
        return write("map.yaml", "image: map.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
                + "occupied_thresh: 0.65\nfree_thresh: 0.196\n" + extra);
    }

    @Test
    void theLabMapNamesItsLandmarksAndStillLoadsAsAMapServerMap() throws IOException {
        Path lab = labYaml();
        List<MapLandmark> marks = MapServerFormat.readLandmarks(lab);
        assertEquals(10, marks.size());
        assertEquals(new MapLandmark(5, 5.6, 3.6), marks.get(4));
        assertEquals(List.of(1, 2, 3, 4, 5, 6, 7, 8, 9, 10), marks.stream().map(MapLandmark::id).toList());
        MapServerFormat.LoadedMap map = MapServerFormat.load(lab);
        for (MapLandmark m : marks) {
            Cell c = map.grid().geometry().cellAt(new Point2D(m.x(), m.y()))
                    .orElseThrow(() -> new AssertionError(m + " is outside the lab"));
            assertEquals(OccupancyGrid.FREE, map.grid().get(c.column(), c.row()), m + " is not above free floor");
        }
    }

    @Test
    void commentsBlankLinesTabsAndCarriageReturnsAreAllowed() throws IOException {
        write("lm.txt", "# markers\n\n  3 -1.5 2e-1  # trailing comment\r\n\t9\t4\t+5.\r\n65535 .5 0\n");
        Path map = yaml("sabot_landmarks: lm.txt   # ignored by map_server\n");
        assertEquals(List.of(new MapLandmark(3, -1.5, 0.2), new MapLandmark(9, 4, 5), new MapLandmark(65535, 0.5, 0)),
                MapServerFormat.readLandmarks(map));
    }

    @Test
    void aMapWithoutTheKeyHasNoLandmarks() throws IOException {
        assertEquals(List.of(), MapServerFormat.readLandmarks(yaml("")));
    }

    @ParameterizedTest
    @CsvSource(delimiter = '|', value = {
        "1 1.0 2.0\\n2 3.0                | 2: expected 'id x y', got 2 fields",
        "# c\\n\\n1 1 2 3                 | 3: expected 'id x y', got 4 fields",
        "5                                | 1: expected 'id x y', got 1 field",
        "0 1.0 2.0                        | 1: id '0' is not an integer in 1..65535",
        "65536 1.0 2.0                    | 1: id '65536' is not an integer in 1..65535",
        "1.5 1.0 2.0                      | 1: id '1.5' is not an integer in 1..65535",
        "7 east 2.0                       | 1: x 'east' is not a number (metres)",
        "7 1.0 NaN                        | 1: y 'NaN' is not a number (metres)",
        "7 1.0 0x10                       | 1: y '0x10' is not a number (metres)",
        "7 1.0 2d                         | 1: y '2d' is not a number (metres)",
        "7 1 1\\n8 2 2 # b\\n7 3 3        | 3: landmark id 7 given twice (first on line 1)",
    })
    void aBadLineIsRefusedWithFileAndLine(String text, String problem) throws IOException {
        Path file = write("bad.landmarks", text.replace("\\n", "\n"));
        Path map = yaml("sabot_landmarks: bad.landmarks\n");
        MapFormatException e = assertThrows(MapFormatException.class, () -> MapServerFormat.readLandmarks(map));
        assertEquals(file + ":" + problem, e.getMessage());
    }

    @Test
    void aMissingOrUnnamedLandmarksFileIsAClearError() throws IOException {
        Path map = yaml("sabot_landmarks: gone.landmarks\n");
        MapFormatException missing = assertThrows(MapFormatException.class, () -> MapServerFormat.readLandmarks(map));
        assertEquals(dir.resolve("gone.landmarks") + ": landmarks file does not exist", missing.getMessage());
        Path empty = yaml("sabot_landmarks:\n");
        MapFormatException unnamed = assertThrows(MapFormatException.class,
                () -> MapServerFormat.readLandmarks(empty));
        assertEquals(empty + ": key 'sabot_landmarks' must name a file", unnamed.getMessage());
    }

    @Test
    void aLandmarkChecksItsIdAndPosition() {
        assertEquals("landmark id must be in 1..65535, got 0",
                assertThrows(IllegalArgumentException.class, () -> new MapLandmark(0, 1, 1)).getMessage());
        assertEquals("landmark 4 position must be finite, got (NaN, 1.0)",
                assertThrows(IllegalArgumentException.class, () -> new MapLandmark(4, Double.NaN, 1)).getMessage());
    }

    /** onboard-bridge/maps/lab.yaml, found from the test's working directory upward (it is inside the checkout). */
    private static Path labYaml() {
        for (Path d = Path.of("").toAbsolutePath(); d != null; d = d.getParent()) {
            Path candidate = d.resolve("onboard-bridge/maps/lab.yaml");
            if (Files.isRegularFile(candidate)) {
                return candidate;
            }
        }
        throw new AssertionError("no onboard-bridge/maps/lab.yaml above " + Path.of("").toAbsolutePath());
    }
}
