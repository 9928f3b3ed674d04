package sabot.model.map;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.regex.Pattern;

import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;

/**
 * Reads and writes maps in the ROS {@code map_server} format: a YAML file ({@code image}, {@code resolution},
 * {@code origin}, {@code negate}, {@code occupied_thresh}, {@code free_thresh}, optional {@code mode}) next to an
 * 8-bit PGM image. Pixel rules follow {@code map_server/src/image_loader.cpp}: with {@code p} the pixel value
 * (replaced by {@code 255 - p} when negated), occupancy probability {@code occ = (255 - p) / 255};
 * {@code occ > occupied_thresh} is occupied (100), {@code occ < free_thresh} free (0), otherwise unknown (-1) in
 * trinary mode or {@code 99 * (occ - free) / (occupied - free)} in scale mode; raw mode keeps {@code p}. Writing picks,
 * for every cell value, a pixel that reads back as the same value under the given metadata (like {@code map_saver}:
 * 254 free, 0 occupied, 205 unknown for the defaults).
 *
 * <p>The YAML reader understands the flat {@code key: value} subset these files use ({@code #} comments, quoted
 * strings, a {@code [x, y, yaw]} list for the origin) and nothing more, so the model stays free of dependencies.
 *
 * <p>Sabot extends the YAML with three keys, {@value #LANDMARKS_KEY}: the file listing the map's ceiling landmarks
 * ({@link #readLandmarks}), {@value #DOCKS_KEY}: the charging docks ({@link #readDocks}), and {@value #PASSAGES_KEY}:
 * the narrow passages robots pass one at a time ({@link #readPassages}). {@code map_server}
 * reads only the keys it knows, so such a map still loads there.
 */
public final class MapServerFormat {

    /** A loaded map: the grid and the description it was read with. */
    public record LoadedMap(OccupancyGrid grid, MapMetadata metadata) {
    }

    /** The YAML key naming the landmarks file, relative to the YAML file's folder unless absolute. */
    public static final String LANDMARKS_KEY = "sabot_landmarks";

    /** The YAML key listing the charging docks: a flow sequence of points, {@code [[x, y], ...]}, metres, map frame. */
    public static final String DOCKS_KEY = "sabot_docks";
    /** At most this many docks, as the simulator reads them (onboard-bridge/sim/world.h, WORLD_MAX_DOCKS). */
    public static final int MAX_DOCKS = 16;
    /** Key of the map's narrow passages ({@link #readPassages}). */
    public static final String PASSAGES_KEY = "sabot_passages";
    /** At most this many passages. */
    public static final int MAX_PASSAGES = 64;
    /** One inner list of a list of lists: the text between its brackets. */
    private static final Pattern TUPLE = Pattern.compile("\\[([^\\[\\]]*)\\]");

    /** A decimal number as the landmarks file writes it (no hex, no {@code NaN}, no {@code 1d}: as the C reader). */
    private static final Pattern DECIMAL = Pattern.compile("[+-]?(\\d+\\.?\\d*|\\.\\d+)([eE][+-]?\\d+)?");

    private static final List<String> REQUIRED_KEYS = List.of("image", "resolution", "origin", "negate",
            "occupied_thresh", "free_thresh");

    private MapServerFormat() {
    }

    /**
     * @param yamlFile the map's YAML description
     * @return the grid (row 0 at the bottom) and its metadata
     * @throws MapFormatException naming the file and the problem: missing file, missing or malformed key, image that
     *                            does not exist or is not a readable PGM
     */
    public static LoadedMap load(Path yamlFile) throws IOException {
        MapMetadata metadata = readMetadata(yamlFile);
        Path imageFile = resolveImage(yamlFile, metadata.image());
        checkPgm(yamlFile, metadata);
        if (!Files.exists(imageFile)) {
            throw new MapFormatException(yamlFile, "image '" + metadata.image() + "' does not exist (looked at " + imageFile + ")");
        }
        return grid(metadata, PgmImage.read(imageFile));
    }

    /**
     * A map held in memory, as a copy from elsewhere gives it (a robot's remote files): the same rules as
     * {@link #load(Path)}, without a file system.
     *
     * @param yamlName where the YAML came from, named in the errors; the image's name is taken relative to it
     * @param yaml     the YAML description, UTF-8
     * @param image    the image the YAML names, its bytes (read them with {@link #readMetadata(Path, byte[])}'s
     *                 {@link MapMetadata#image()})
     * @return the grid (row 0 at the bottom) and its metadata
     * @throws MapFormatException naming the YAML or the image and the problem
     */
    public static LoadedMap load(Path yamlName, byte[] yaml, byte[] image) throws MapFormatException {
        MapMetadata metadata = readMetadata(yamlName, yaml);
        checkPgm(yamlName, metadata);
        return grid(metadata, PgmImage.parse(resolveImage(yamlName, metadata.image()), image));
    }

    private static void checkPgm(Path yamlFile, MapMetadata metadata) throws MapFormatException {
        Path image = Path.of(metadata.image()).getFileName();
        if (image == null || !image.toString().toLowerCase(Locale.ROOT).endsWith(".pgm")) {
            throw new MapFormatException(yamlFile, "image '" + metadata.image() + "' is not a .pgm file (only PGM is supported)");
        }
    }

    private static LoadedMap grid(MapMetadata metadata, PgmImage image) {
        byte[] lookup = pixelToValue(metadata);
        int width = image.width();
        int height = image.height();
        byte[] values = new byte[width * height];
        for (int imageRow = 0; imageRow < height; imageRow++) {
            int row = height - 1 - imageRow;
            for (int column = 0; column < width; column++) {
                values[row * width + column] = lookup[image.pixel(column, imageRow)];
            }
        }
        GridGeometry geometry = new GridGeometry(width, height, metadata.resolution(), metadata.origin());
        return new LoadedMap(OccupancyGrid.of(geometry, values), metadata);
    }

    /**
     * Writes {@code yamlFile} and the image it names (relative to the YAML file's folder unless absolute), so that
     * {@link #load} returns the same grid.
     *
     * @param metadata how to encode pixels; its resolution and origin must be the grid's
     * @throws IllegalArgumentException when the metadata disagrees with the grid, or cannot encode one of its values
     *                                  (e.g. a graded value in trinary mode)
     */
    public static void save(OccupancyGrid grid, MapMetadata metadata, Path yamlFile) throws IOException {
        GridGeometry geometry = grid.geometry();
        if (metadata.resolution() != geometry.resolution() || !metadata.origin().equals(geometry.origin())) {
            throw new IllegalArgumentException("metadata resolution/origin (" + metadata.resolution() + ", "
                    + metadata.origin() + ") differ from the grid's (" + geometry.resolution() + ", " + geometry.origin() + ")");
        }
        int[] valueToPixel = valueToPixel(metadata);
        int width = grid.width();
        int height = grid.height();
        byte[] pixels = new byte[width * height];
        for (int row = 0; row < height; row++) {
            int imageRow = height - 1 - row;
            for (int column = 0; column < width; column++) {
                int value = grid.get(column, row);
                int pixel = valueToPixel[value + 1];
                if (pixel < 0) {
                    throw new IllegalArgumentException("cell (" + column + ", " + row + ") value " + value
                            + " cannot be written in " + metadata.mode().yamlName() + " mode with these thresholds");
                }
                pixels[imageRow * width + column] = (byte) pixel;
            }
        }
        new PgmImage(width, height, pixels).write(resolveImage(yamlFile, metadata.image()));
        Files.writeString(yamlFile, toYaml(metadata), StandardCharsets.UTF_8);
    }

    /**
     * Reads a raw 8-bit costmap image in the ROS {@code costmap_2d} convention (0 free, 1..252 graded, 253 inscribed,
     * 254 lethal, 255 unknown): each pixel value is the cell's cost, the image's top row is the map's top row.
     *
     * @param resolution metres per pixel
     * @param origin     map-frame pose of the lower-left pixel's corner
     */
    public static Costmap loadCostmapImage(Path pgmFile, double resolution, Pose2D origin) throws IOException {
        PgmImage image = PgmImage.read(pgmFile);
        GridGeometry geometry = new GridGeometry(image.width(), image.height(), resolution, origin);
        byte[] flipped = new byte[geometry.cellCount()];
        byte[] pixels = image.toArray();
        for (int imageRow = 0; imageRow < image.height(); imageRow++) {
            System.arraycopy(pixels, imageRow * image.width(), flipped, (image.height() - 1 - imageRow) * image.width(),
                    image.width());
        }
        return Costmap.of(geometry, flipped);
    }

    /** Writes a costmap as a raw 8-bit PGM, top row of the map first (the inverse of {@link #loadCostmapImage}). */
    public static void saveCostmapImage(Costmap costmap, Path pgmFile) throws IOException {
        int width = costmap.width();
        int height = costmap.height();
        byte[] pixels = new byte[width * height];
        for (int row = 0; row < height; row++) {
            costmap.copyRow(row, 0, width - 1, pixels, (height - 1 - row) * width);
        }
        new PgmImage(width, height, pixels).write(pgmFile);
    }

    /**
     * @return the metadata of a map YAML file
     * @throws MapFormatException naming the file and the missing or malformed key
     */
    public static MapMetadata readMetadata(Path yamlFile) throws IOException {
        return metadata(yamlFile, readText(yamlFile, "map file"));
    }

    /**
     * @param yamlName where the YAML came from, named in the errors
     * @param yaml     a map's YAML description, UTF-8
     * @return its metadata
     * @throws MapFormatException naming {@code yamlName} and the missing or malformed key
     */
    public static MapMetadata readMetadata(Path yamlName, byte[] yaml) throws MapFormatException {
        try {
            return metadata(yamlName, StandardCharsets.UTF_8.newDecoder().decode(java.nio.ByteBuffer.wrap(yaml))
                    .toString());
        } catch (java.nio.charset.CharacterCodingException e) {
            throw new MapFormatException(yamlName, "not a UTF-8 text file");
        }
    }

    private static MapMetadata metadata(Path yamlFile, String text) throws MapFormatException {
        Map<String, String> keys = parseFlatYaml(yamlFile, text);
        for (String key : REQUIRED_KEYS) {
            if (!keys.containsKey(key)) {
                throw new MapFormatException(yamlFile, "missing key '" + key + "'");
            }
        }
        String image = keys.get("image");
        double resolution = number(yamlFile, keys, "resolution");
        Pose2D origin = origin(yamlFile, keys.get("origin"));
        boolean negate = bool(yamlFile, keys, "negate");
        double occupied = number(yamlFile, keys, "occupied_thresh");
        double free = number(yamlFile, keys, "free_thresh");
        MapMode mode = MapMode.TRINARY;
        if (keys.containsKey("mode")) {
            mode = MapMode.fromYamlName(keys.get("mode")).orElseThrow(() -> new MapFormatException(yamlFile,
                    "key 'mode' is '" + keys.get("mode") + "', expected trinary, scale or raw"));
        }
        try {
            return new MapMetadata(image, resolution, origin, negate, occupied, free, mode);
        } catch (IllegalArgumentException e) {
            throw new MapFormatException(yamlFile, e.getMessage());
        }
    }

    /**
     * The ceiling landmarks of a map: the file its YAML names under {@value #LANDMARKS_KEY}, read by
     * {@link #readLandmarkFile}.
     *
     * @param yamlFile the map's YAML description
     * @return the landmarks in file order; empty when the YAML has no {@value #LANDMARKS_KEY} key
     * @throws MapFormatException naming the file (and line) at fault: the YAML unreadable or the key empty, the
     *                            landmarks file missing or malformed
     */
    /**
     * The charging docks of a map: its YAML's {@value #DOCKS_KEY}, e.g. {@code sabot_docks: [[1.0, 1.0], [11.0, 1.0]]}
     * (the simulator charges a robot whose centre is within 0.15 m of one).
     *
     * @param yamlFile the map's YAML description
     * @return the docks' points in the map frame, m, in the YAML's order; empty when the YAML has no such key
     * @throws MapFormatException naming the file and what is wrong: not a list of [x, y] pairs of finite numbers, or
     *                            more than {@value #MAX_DOCKS}
     */
    public static List<Point2D> readDocks(Path yamlFile) throws IOException {
        List<double[]> tuples = readTuples(yamlFile, DOCKS_KEY, 2, "[[x, y], ...] (numbers, metres)");
        if (tuples.size() > MAX_DOCKS) {
            throw new MapFormatException(yamlFile, "key '" + DOCKS_KEY + "' lists " + tuples.size()
                    + " docks, at most " + MAX_DOCKS);
        }
        return tuples.stream().map(t -> new Point2D(t[0], t[1])).toList();
    }

    /**
     * The narrow passages of a map, where robots pass one at a time (docs/PASSAGES.md): its YAML's
     * {@value #PASSAGES_KEY}, e.g. {@code sabot_passages: [[4.2, 1.7, 4.4, 2.7]]}, each the rectangle
     * {@code [minX, minY, maxX, maxY]} of the narrow part (a door's opening, a corridor), metres in the map frame.
     *
     * @param yamlFile the map's YAML description
     * @return the passages, numbered from 1 in the YAML's order; empty when the YAML has no such key
     * @throws MapFormatException naming the file and what is wrong: not a list of four finite numbers each, a
     *                            rectangle whose maximum is not above its minimum, or more than {@value #MAX_PASSAGES}
     */
    public static List<Passage> readPassages(Path yamlFile) throws IOException {
        List<double[]> tuples = readTuples(yamlFile, PASSAGES_KEY, 4,
                "[[minX, minY, maxX, maxY], ...] (numbers, metres)");
        if (tuples.size() > MAX_PASSAGES) {
            throw new MapFormatException(yamlFile, "key '" + PASSAGES_KEY + "' lists " + tuples.size()
                    + " passages, at most " + MAX_PASSAGES);
        }
        List<Passage> out = new ArrayList<>();
        for (double[] t : tuples) {
            if (!(t[2] > t[0]) || !(t[3] > t[1])) {
                throw new MapFormatException(yamlFile, "key '" + PASSAGES_KEY + "': passage " + (out.size() + 1)
                        + " [" + t[0] + ", " + t[1] + ", " + t[2] + ", " + t[3] + "] is not a rectangle: maxX must "
                        + "be above minX and maxY above minY");
            }
            out.add(new Passage(out.size() + 1, t[0], t[1], t[2], t[3]));
        }
        return List.copyOf(out);
    }

    /**
     * Reads a key whose value is a list of lists of {@code arity} numbers, {@code [[a, b], [c, d]]}.
     *
     * @return the lists in order; empty when the key is absent
     * @throws MapFormatException "key 'K' is 'V', expected EXPECTED" when the value is anything else
     */
    private static List<double[]> readTuples(Path yamlFile, String key, int arity, String expected)
            throws IOException {
        String value = parseFlatYaml(yamlFile, readText(yamlFile, "map file")).get(key);
        if (value == null) {
            return List.of();
        }
        String v = value.strip();
        MapFormatException bad = new MapFormatException(yamlFile, "key '" + key + "' is '" + value + "', expected "
                + expected);
        if (!v.startsWith("[") || !v.endsWith("]")) {
            throw bad;
        }
        String inner = v.substring(1, v.length() - 1).strip();
        List<double[]> tuples = new ArrayList<>();
        java.util.regex.Matcher m = TUPLE.matcher(inner);
        int at = 0;
        while (at < inner.length()) {
            if (!m.find(at) || m.start() != at) {
                throw bad;
            }
            String[] parts = m.group(1).split(",", -1);
            if (parts.length != arity) {
                throw bad;
            }
            double[] t = new double[arity];
            for (int i = 0; i < arity; i++) {
                t[i] = tupleNumber(parts[i].strip(), bad);
            }
            tuples.add(t);
            at = m.end();
            while (at < inner.length() && Character.isWhitespace(inner.charAt(at))) {
                at++;
            }
            if (at < inner.length()) {
                if (inner.charAt(at) != ',') {
                    throw bad;
                }
                at++;
                while (at < inner.length() && Character.isWhitespace(inner.charAt(at))) {
                    at++;
                }
                if (at == inner.length()) {
                    throw bad;
                }
            }
        }
        return tuples;
    }

    private static double tupleNumber(String text, MapFormatException bad) throws MapFormatException {
        if (!DECIMAL.matcher(text).matches()) {
            throw bad;
        }
        return Double.parseDouble(text);
    }

    public static List<MapLandmark> readLandmarks(Path yamlFile) throws IOException {
        String name = parseFlatYaml(yamlFile, readText(yamlFile, "map file")).get(LANDMARKS_KEY);
        if (name == null) {
            return List.of();
        }
        if (name.isBlank()) {
            throw new MapFormatException(yamlFile, "key '" + LANDMARKS_KEY + "' must name a file");
        }
        return readLandmarkFile(resolveImage(yamlFile, name));
    }

    /**
     * Reads a landmarks file: one marker per line, {@code id x y} separated by blanks ({@code id} an integer
     * 1–65535, {@code x} and {@code y} decimal metres in the map frame), {@code #} starting a comment, blank lines
     * allowed, every id once. The simulator's world loader reads the same format.
     *
     * @return the landmarks in file order
     * @throws MapFormatException naming the file and line: a line without exactly three fields, an id that is not an
     *                            integer in range, a coordinate that is not a decimal number, an id given twice
     */
    public static List<MapLandmark> readLandmarkFile(Path file) throws IOException {
        String[] lines = readText(file, "landmarks file").split("\r?\n|\r", -1);
        List<MapLandmark> landmarks = new ArrayList<>();
        Map<Integer, Integer> lineOfId = new HashMap<>();
        for (int i = 0; i < lines.length; i++) {
            int lineNo = i + 1;
            String line = lines[i];
            int hash = line.indexOf('#');
            String content = (hash >= 0 ? line.substring(0, hash) : line).strip();
            if (content.isEmpty()) {
                continue;
            }
            String[] fields = content.split("\\s+");
            if (fields.length != 3) {
                throw new MapFormatException(file, lineNo, "expected 'id x y', got " + fields.length
                        + (fields.length == 1 ? " field" : " fields"));
            }
            int id;
            try {
                id = Integer.parseInt(fields[0]);
            } catch (NumberFormatException e) {
                id = -1;
            }
            if (id < MapLandmark.MIN_ID || id > MapLandmark.MAX_ID) {
                throw new MapFormatException(file, lineNo, "id '" + fields[0] + "' is not an integer in "
                        + MapLandmark.MIN_ID + ".." + MapLandmark.MAX_ID);
            }
            double x = coordinate(file, lineNo, "x", fields[1]);
            double y = coordinate(file, lineNo, "y", fields[2]);
            Integer first = lineOfId.putIfAbsent(id, lineNo);
            if (first != null) {
                throw new MapFormatException(file, lineNo, "landmark id " + id + " given twice (first on line "
                        + first + ")");
            }
            landmarks.add(new MapLandmark(id, x, y));
        }
        return List.copyOf(landmarks);
    }

    /** @return the whole of a UTF-8 text file; {@code what} names it when it does not exist */
    private static String readText(Path file, String what) throws IOException {
        try {
            return Files.readString(file, StandardCharsets.UTF_8);
        } catch (NoSuchFileException e) {
            throw new MapFormatException(file, what + " does not exist");
        } catch (java.nio.charset.MalformedInputException e) {
            throw new MapFormatException(file, "not a UTF-8 text file");
        }
    }

    private static double coordinate(Path file, int line, String name, String text) throws MapFormatException {
        if (DECIMAL.matcher(text).matches()) {
            double v = Double.parseDouble(text);
            if (Double.isFinite(v)) {
                return v;
            }
        }
        throw new MapFormatException(file, line, name + " '" + text + "' is not a number (metres)");
    }

    /** @return the YAML text describing a map, in {@code map_saver}'s layout */
    public static String toYaml(MapMetadata metadata) {
        Pose2D o = metadata.origin();
        StringBuilder yaml = new StringBuilder();
        yaml.append("image: ").append(metadata.image()).append('\n');
        yaml.append("resolution: ").append(metadata.resolution()).append('\n');
        yaml.append("origin: [").append(o.x()).append(", ").append(o.y()).append(", ").append(o.theta()).append("]\n");
        yaml.append("negate: ").append(metadata.negate() ? 1 : 0).append('\n');
        yaml.append("occupied_thresh: ").append(metadata.occupiedThresh()).append('\n');
        yaml.append("free_thresh: ").append(metadata.freeThresh()).append('\n');
        if (metadata.mode() != MapMode.TRINARY) {
            yaml.append("mode: ").append(metadata.mode().yamlName()).append('\n');
        }
        return yaml.toString();
    }

    /** @return for every pixel value 0..255 the cell value it loads as */
    static byte[] pixelToValue(MapMetadata metadata) {
        byte[] lookup = new byte[256];
        for (int pixel = 0; pixel < 256; pixel++) {
            int shade = metadata.negate() ? 255 - pixel : pixel;
            int value;
            if (metadata.mode() == MapMode.RAW) {
                value = shade <= OccupancyGrid.OCCUPIED ? shade : OccupancyGrid.UNKNOWN;
            } else {
                double occ = (255 - shade) / 255.0;
                if (occ > metadata.occupiedThresh()) {
                    value = OccupancyGrid.OCCUPIED;
                } else if (occ < metadata.freeThresh()) {
                    value = OccupancyGrid.FREE;
                } else if (metadata.mode() == MapMode.TRINARY) {
                    value = OccupancyGrid.UNKNOWN;
                } else {
                    double ratio = (occ - metadata.freeThresh()) / (metadata.occupiedThresh() - metadata.freeThresh());
                    value = (int) (99 * ratio);
                }
            }
            lookup[pixel] = (byte) value;
        }
        return lookup;
    }

    /**
     * @return for every cell value -1..100 (at index value + 1) a pixel that loads as that value, or -1 when none does;
     *         prefers {@code map_saver}'s choices (254 free, 0 occupied, 205 unknown) when they work
     */
    static int[] valueToPixel(MapMetadata metadata) {
        byte[] lookup = pixelToValue(metadata);
        int[] pixelOf = new int[102];
        java.util.Arrays.fill(pixelOf, -1);
        int[] preferred = { 254, 0, 205 };
        for (int shade : preferred) {
            int pixel = metadata.negate() ? 255 - shade : shade;
            int value = lookup[pixel];
            if (pixelOf[value + 1] < 0) {
                pixelOf[value + 1] = pixel;
            }
        }
        for (int pixel = 0; pixel < 256; pixel++) {
            int value = lookup[pixel];
            if (pixelOf[value + 1] < 0) {
                pixelOf[value + 1] = pixel;
            }
        }
        return pixelOf;
    }

    private static Path resolveImage(Path yamlFile, String image) {
        Path imagePath = Path.of(image);
        if (imagePath.isAbsolute()) {
            return imagePath;
        }
        Path folder = yamlFile.toAbsolutePath().getParent();
        return folder == null ? imagePath : folder.resolve(imagePath);
    }

    private static Map<String, String> parseFlatYaml(Path file, String text) throws MapFormatException {
        Map<String, String> keys = new LinkedHashMap<>();
        String[] lines = text.split("\r?\n|\r", -1);
        for (int i = 0; i < lines.length; i++) {
            String line = stripComment(lines[i]).strip();
            if (line.isEmpty() || line.equals("---") || line.equals("...")) {
                continue;
            }
            int colon = line.indexOf(':');
            if (colon <= 0) {
                throw new MapFormatException(file, "line " + (i + 1) + " is not 'key: value': '" + line + "'");
            }
            String key = line.substring(0, colon).strip();
            String value = unquote(line.substring(colon + 1).strip());
            if (keys.put(key, value) != null) {
                throw new MapFormatException(file, "key '" + key + "' appears twice (line " + (i + 1) + ")");
            }
        }
        return keys;
    }

    private static String stripComment(String line) {
        char quote = 0;
        for (int i = 0; i < line.length(); i++) {
            char c = line.charAt(i);
            if (quote != 0) {
                if (c == quote) {
                    quote = 0;
                }
            } else if (c == '"' || c == '\'') {
                quote = c;
            } else if (c == '#' && (i == 0 || Character.isWhitespace(line.charAt(i - 1)))) {
                return line.substring(0, i);
            }
        }
        return line;
    }

    private static String unquote(String value) {
        if (value.length() >= 2 && (value.startsWith("\"") && value.endsWith("\"")
                || value.startsWith("'") && value.endsWith("'"))) {
            return value.substring(1, value.length() - 1);
        }
        return value;
    }

    private static double number(Path file, Map<String, String> keys, String key) throws MapFormatException {
        String value = keys.get(key);
        try {
            double parsed = Double.parseDouble(value);
            if (Double.isFinite(parsed)) {
                return parsed;
            }
        } catch (NumberFormatException e) {
            // reported below
        }
        throw new MapFormatException(file, "key '" + key + "' is '" + value + "', expected a number");
    }

    private static boolean bool(Path file, Map<String, String> keys, String key) throws MapFormatException {
        String value = keys.get(key).toLowerCase(Locale.ROOT);
        return switch (value) {
            case "0", "false", "no" -> false;
            case "1", "true", "yes" -> true;
            default -> throw new MapFormatException(file, "key '" + key + "' is '" + keys.get(key) + "', expected 0 or 1");
        };
    }

    private static Pose2D origin(Path file, String value) throws MapFormatException {
        String inner = value.strip();
        if (!inner.startsWith("[") || !inner.endsWith("]")) {
            throw new MapFormatException(file, "key 'origin' is '" + value + "', expected [x, y, yaw]");
        }
        String[] parts = inner.substring(1, inner.length() - 1).split(",");
        if (parts.length != 3) {
            throw new MapFormatException(file, "key 'origin' has " + parts.length + " values, expected [x, y, yaw]");
        }
        double[] numbers = new double[3];
        for (int i = 0; i < 3; i++) {
            try {
                numbers[i] = Double.parseDouble(parts[i].strip());
            } catch (NumberFormatException e) {
                throw new MapFormatException(file, "key 'origin' value '" + parts[i].strip() + "' is not a number");
            }
            if (!Double.isFinite(numbers[i])) {
                throw new MapFormatException(file, "key 'origin' value '" + parts[i].strip() + "' is not finite");
            }
        }
        return new Pose2D(numbers[0], numbers[1], numbers[2]);
    }
}
