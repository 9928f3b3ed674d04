package sabot.model.map;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Random;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

import sabot.model.geometry.Pose2D;

/** ROS map_server PGM + YAML: round trips and clear errors. */
class MapServerFormatTest {

    @TempDir
    Path folder;

    private static OccupancyGrid randomGrid(long seed, boolean graded) {
        Random random = new Random(seed);
        OccupancyGrid grid = OccupancyGrid.unknown(37, 23, 0.05, new Pose2D(-1.25, 3.5, 0));
        for (int r = 0; r < grid.height(); r++) {
            for (int c = 0; c < grid.width(); c++) {
                int kind = random.nextInt(3);
                int value = kind == 0 ? OccupancyGrid.FREE : kind == 1 ? OccupancyGrid.OCCUPIED : OccupancyGrid.UNKNOWN;
                if (graded && kind == 2) {
                    value = random.nextInt(100);
                }
                grid.set(c, r, value);
            }
        }
        return grid;
    }

    @ParameterizedTest
    @CsvSource({ "false, 0.65, 0.196", "true, 0.65, 0.196", "false, 0.9, 0.05", "true, 0.6, 0.4" })
    void trinaryMapSurvivesARoundTripWithNegateAndThresholds(boolean negate, double occupied, double free)
            throws IOException {
        OccupancyGrid grid = randomGrid(1, false);
        MapMetadata metadata = new MapMetadata("lab.pgm", grid.resolution(), grid.geometry().origin(), negate, occupied,
                free, MapMode.TRINARY);
        Path yaml = folder.resolve("lab.yaml");
        MapServerFormat.save(grid, metadata, yaml);
        MapServerFormat.LoadedMap loaded = MapServerFormat.load(yaml);
        assertTrue(grid.sameAs(loaded.grid()), "grid differs after the round trip");
        assertEquals(metadata, loaded.metadata());
        // and once more from the files written by the first load's data
        MapServerFormat.save(loaded.grid(), loaded.metadata(), folder.resolve("again.yaml"));
        assertEquals(Files.readString(yaml).replace("lab.pgm", "x"),
                Files.readString(folder.resolve("again.yaml")).replace("lab.pgm", "x"));
    }

    @ParameterizedTest
    @CsvSource({ "SCALE, false", "SCALE, true", "RAW, false", "RAW, true" })
    void gradedMapSurvivesARoundTripInScaleAndRawModes(MapMode mode, boolean negate) throws IOException {
        OccupancyGrid grid = randomGrid(2, true);
        MapMetadata metadata = new MapMetadata("graded.pgm", grid.resolution(), grid.geometry().origin(), negate, 0.65,
                0.196, mode);
        Path yaml = folder.resolve("graded.yaml");
        if (mode == MapMode.SCALE) {
            // scale mode cannot express every percentage: 99 * ratio is truncated; round-trip what it can
            byte[] values = grid.toArray();
            MapServerFormat.save(grid.geometry().width() > 0 ? reencodable(grid, metadata) : grid, metadata, yaml);
            assertTrue(values.length > 0);
        } else {
            MapServerFormat.save(grid, metadata, yaml);
            assertTrue(grid.sameAs(MapServerFormat.load(yaml).grid()), "grid differs after the round trip");
        }
    }

    private OccupancyGrid reencodable(OccupancyGrid grid, MapMetadata metadata) throws IOException {
        // a first save/load maps every value to one the format can hold; from then on the round trip is exact
        Path first = folder.resolve("first.yaml");
        OccupancyGrid trinary = OccupancyGrid.unknown(grid.width(), grid.height(), grid.resolution(),
                grid.geometry().origin());
        for (int r = 0; r < grid.height(); r++) {
            for (int c = 0; c < grid.width(); c++) {
                int v = grid.get(c, r);
                trinary.set(c, r, v == OccupancyGrid.UNKNOWN || v == OccupancyGrid.OCCUPIED ? v : 0);
            }
        }
        MapServerFormat.save(trinary, metadata, first);
        OccupancyGrid loaded = MapServerFormat.load(first).grid();
        MapServerFormat.save(loaded, metadata, folder.resolve("second.yaml"));
        assertTrue(loaded.sameAs(MapServerFormat.load(folder.resolve("second.yaml")).grid()));
        return loaded;
    }

    @Test
    void imageRowsAreFlippedSoRowZeroIsTheBottomOfTheMap() throws IOException {
        Files.write(folder.resolve("tiny.pgm"), pgm(2, 2, new int[] { 0, 254, 254, 254 }));
        Files.writeString(folder.resolve("tiny.yaml"), """
                image: tiny.pgm   # top-left pixel black
                resolution: 0.5
                origin: [ 1.0, -2.0, 0.0 ]
                negate: 0
                occupied_thresh: 0.65
                free_thresh: 0.196
                """);
        OccupancyGrid grid = MapServerFormat.load(folder.resolve("tiny.yaml")).grid();
        assertEquals(OccupancyGrid.OCCUPIED, grid.get(0, 1));
        assertEquals(OccupancyGrid.FREE, grid.get(0, 0));
        assertEquals(new Pose2D(1.0, -2.0, 0.0), grid.geometry().origin());
    }

    @Test
    void costmapImageIsReadAsRawCostsWithTheTopRowFirst() throws IOException {
        Path file = folder.resolve("costs.pgm");
        Files.write(file, pgm(3, 2, new int[] { 254, 0, 7, 253, 255, 100 }));
        Costmap costmap = MapServerFormat.loadCostmapImage(file, 1.0, Pose2D.ORIGIN);
        assertEquals(Costmap.LETHAL, costmap.cost(0, 1));
        assertEquals(7, costmap.cost(2, 1));
        assertEquals(Costmap.INSCRIBED, costmap.cost(0, 0));
        assertEquals(Costmap.NO_INFORMATION, costmap.cost(1, 0));
        MapServerFormat.saveCostmapImage(costmap, folder.resolve("again.pgm"));
        assertEquals(java.util.Arrays.toString(Files.readAllBytes(file)),
                java.util.Arrays.toString(Files.readAllBytes(folder.resolve("again.pgm"))));
    }

    @Test
    void plainAsciiPgmWithCommentsAndSmallMaximumIsRead() throws IOException {
        Path file = folder.resolve("ascii.pgm");
        Files.writeString(file, "P2\n# made by hand\n2 1\n15\n0 15\n");
        PgmImage image = PgmImage.read(file);
        assertEquals(0, image.pixel(0, 0));
        assertEquals(255, image.pixel(1, 0));
    }

    @ParameterizedTest
    @CsvSource(delimiter = '|', quoteCharacter = '"', value = {
            "P5\\n4 4\\n255\\nabc|truncated PGM: expected 16 pixel bytes, found 3",
            "P6\\n1 1\\n255\\nx|not a PGM image",
            "P5\\n0 4\\n255\\n|width is '0'",
            "P5\\n4|truncated PGM header: missing height",
            "P5\\n2 2\\n65535\\n|16-bit PGM",
            "P2\\n2 1\\n255\\n0 x|pixel 1 is 'x'",
            "P2\\n2 1\\n255\\n0|truncated PGM: expected 2 pixel values, found 1" })
    void malformedPgmIsAClearError(String content, String expected) throws IOException {
        Path file = folder.resolve("bad.pgm");
        Files.writeString(file, content.replace("\\n", "\n"), StandardCharsets.ISO_8859_1);
        MapFormatException e = assertThrows(MapFormatException.class, () -> PgmImage.read(file));
        assertTrue(e.getMessage().contains(expected) && e.getMessage().contains("bad.pgm"), e.getMessage());
    }

    @ParameterizedTest
    @CsvSource(delimiter = '|', quoteCharacter = '"', value = {
            "resolution: 0.05\\norigin: [0, 0, 0]\\nnegate: 0\\noccupied_thresh: 0.65\\nfree_thresh: 0.196|missing key 'image'",
            "image: m.pgm\\norigin: [0, 0, 0]\\nnegate: 0\\noccupied_thresh: 0.65\\nfree_thresh: 0.196|missing key 'resolution'",
            "image: m.pgm\\nresolution: 0.05\\nnegate: 0\\noccupied_thresh: 0.65\\nfree_thresh: 0.196|missing key 'origin'",
            "image: m.pgm\\nresolution: 0.05\\norigin: [0, 0, 0]\\noccupied_thresh: 0.65\\nfree_thresh: 0.196|missing key 'negate'",
            "image: m.pgm\\nresolution: -1\\norigin: [0, 0, 0]\\nnegate: 0\\noccupied_thresh: 0.65\\nfree_thresh: 0.196|resolution must be a positive",
            "image: m.pgm\\nresolution: 0\\norigin: [0, 0, 0]\\nnegate: 0\\noccupied_thresh: 0.65\\nfree_thresh: 0.196|resolution must be a positive",
            "image: m.pgm\\nresolution: abc\\norigin: [0, 0, 0]\\nnegate: 0\\noccupied_thresh: 0.65\\nfree_thresh: 0.196|key 'resolution' is 'abc'",
            "image: m.pgm\\nresolution: 0.05\\norigin: [0, 0]\\nnegate: 0\\noccupied_thresh: 0.65\\nfree_thresh: 0.196|expected [x, y, yaw]",
            "image: m.pgm\\nresolution: 0.05\\norigin: [0, 0, 0]\\nnegate: 2\\noccupied_thresh: 0.65\\nfree_thresh: 0.196|expected 0 or 1",
            "image: m.pgm\\nresolution: 0.05\\norigin: [0, 0, 0]\\nnegate: 0\\noccupied_thresh: 0.1\\nfree_thresh: 0.196|must not exceed",
            "image: m.pgm\\nresolution: 0.05\\norigin: [0, 0, 0]\\nnegate: 0\\noccupied_thresh: 0.65\\nfree_thresh: 0.196\\nmode: fancy|expected trinary, scale or raw",
            "image: missing.pgm\\nresolution: 0.05\\norigin: [0, 0, 0]\\nnegate: 0\\noccupied_thresh: 0.65\\nfree_thresh: 0.196|image 'missing.pgm' does not exist",
            "image: map.png\\nresolution: 0.05\\norigin: [0, 0, 0]\\nnegate: 0\\noccupied_thresh: 0.65\\nfree_thresh: 0.196|only PGM is supported",
            "just some text|is not 'key: value'" })
    void badYamlIsAClearErrorNamingTheProblem(String yaml, String expected) throws IOException {
        Path file = folder.resolve("map.yaml");
        Files.writeString(file, yaml.replace("\\n", "\n"));
        Files.write(folder.resolve("m.pgm"), pgm(1, 1, new int[] { 254 }));
        MapFormatException e = assertThrows(MapFormatException.class, () -> MapServerFormat.load(file));
        assertTrue(e.getMessage().contains(expected) && e.getMessage().contains("map.yaml"), e.getMessage());
    }

    @Test
    void missingYamlFileIsAClearError() {
        MapFormatException e = assertThrows(MapFormatException.class,
                () -> MapServerFormat.load(folder.resolve("nowhere.yaml")));
        assertTrue(e.getMessage().contains("does not exist"), e.getMessage());
    }

    @ParameterizedTest
    @CsvSource({ "false, TRINARY", "true, TRINARY", "false, RAW", "true, RAW" })
    void aMapHeldInMemoryLoadsAsTheSameMapFromItsFiles(boolean negate, MapMode mode) throws IOException {
        OccupancyGrid grid = randomGrid(3, mode == MapMode.RAW);
        MapMetadata metadata = new MapMetadata("lab.pgm", grid.resolution(), grid.geometry().origin(), negate, 0.65,
                0.196, mode);
        Path yaml = folder.resolve("lab.yaml");
        MapServerFormat.save(grid, metadata, yaml);
        byte[] yamlBytes = Files.readAllBytes(yaml);
        assertEquals(metadata, MapServerFormat.readMetadata(Path.of("robot1", "lab.yaml"), yamlBytes));
        MapServerFormat.LoadedMap fromBytes = MapServerFormat.load(Path.of("robot1", "lab.yaml"), yamlBytes, Files
                .readAllBytes(folder.resolve("lab.pgm")));
        MapServerFormat.LoadedMap fromFiles = MapServerFormat.load(yaml);
        assertTrue(fromFiles.grid().sameAs(fromBytes.grid()), "the grids differ");
        assertTrue(grid.sameAs(fromBytes.grid()), "grid differs after the round trip through bytes");
        assertEquals(fromFiles.metadata(), fromBytes.metadata());
    }

    @ParameterizedTest
    @CsvSource(delimiter = '|', value = {
            "image: m.pgm\\nresolution: 0.05\\nnegate: 0\\noccupied_thresh: 0.65\\nfree_thresh: 0.196|P5\\n1 1\\n255\\n\u00fe|missing key 'origin'|map.yaml",
            "image: map.png\\nresolution: 0.05\\norigin: [0, 0, 0]\\nnegate: 0\\noccupied_thresh: 0.65\\nfree_thresh: 0.196|P5\\n1 1\\n255\\n\u00fe|only PGM is supported|map.yaml",
            "image: m.pgm\\nresolution: 0.05\\norigin: [0, 0, 0]\\nnegate: 0\\noccupied_thresh: 0.65\\nfree_thresh: 0.196|P5\\n2 2\\n255\\n\u00fe|truncated PGM: expected 4 pixel bytes, found 1|m.pgm" })
    void aBadMapHeldInMemoryIsAClearErrorNamingWhereItCameFrom(String yaml, String image, String expected,
            String named) {
        Path from = Path.of("robot1", "map.yaml");
        MapFormatException e = assertThrows(MapFormatException.class, () -> MapServerFormat.load(from, yaml.replace(
                "\\n", "\n").getBytes(StandardCharsets.UTF_8), image.replace("\\n", "\n").getBytes(
                        StandardCharsets.ISO_8859_1)));
        assertTrue(e.getMessage().contains(expected) && e.getMessage().contains(named), e.getMessage());
    }

    @Test
    void aYamlHeldInMemoryThatIsNotUtf8IsAClearError() {
        MapFormatException e = assertThrows(MapFormatException.class, () -> MapServerFormat.readMetadata(Path.of(
                "map.yaml"), new byte[] { 'i', ':', (byte) 0xff, (byte) 0xfe }));
        assertTrue(e.getMessage().contains("not a UTF-8 text file"), e.getMessage());
    }

    @ParameterizedTest
    @CsvSource({ "0, 0, 1.0", "0, 5, 1.0", "5, -1, 1.0", "5, 5, 0", "5, 5, -0.5", "5, 5, NaN" })
    void emptyGridsAndBadResolutionsAreRejected(int width, int height, double resolution) {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> new GridGeometry(width, height, resolution, Pose2D.ORIGIN));
        assertTrue(e.getMessage().contains("cell") || e.getMessage().contains("resolution"), e.getMessage());
    }

    static byte[] pgm(int width, int height, int[] pixels) {
        byte[] header = ("P5\n" + width + " " + height + "\n255\n").getBytes(StandardCharsets.US_ASCII);
        byte[] bytes = java.util.Arrays.copyOf(header, header.length + pixels.length);
        for (int i = 0; i < pixels.length; i++) {
            bytes[header.length + i] = (byte) pixels[i];
        }
        return bytes;
    }
}
