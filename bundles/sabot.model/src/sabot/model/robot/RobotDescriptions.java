package sabot.model.robot;

import java.io.IOException;
import java.io.InputStream;
import java.io.Reader;
import java.io.StringReader;
import java.io.UncheckedIOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.Properties;
import java.util.Set;
import java.util.TreeSet;

/**
 * Loads a {@link RobotDescription} from the robot-description file format: Java properties (ISO-8859-1 escapes
 * allowed, UTF-8 read), one key per constant, the unit written in the key so that a reader never guesses it.
 *
 * <pre>
 * robot.name                      = sabot-1
 * wheel.radius.m                  = 0.075
 * track.width.m                   = 0.40
 * gear.ratio                      = 43
 * encoder.lines                   = 512
 * encoder.quadrature              = 4
 * motor.noLoadSpeed.rpm           = 7740
 * limit.linearSpeed.mps           = 0.5
 * limit.linearAcceleration.mps2   = 0.5
 * limit.angularSpeed.radps        = 2.0
 * limit.lateralAcceleration.mps2  = 0.3
 * control.period.s                = 0.02
 * </pre>
 *
 * Every key is required; unknown keys are an error (a typo must not silently fall back to a default). The reference
 * robot's file is {@code docs/sabot-robot.properties} in the source tree, beside the Modbus map: the one description
 * that Java, the SACT firmware's defaults and the simulator are built from. The build copies it next to this class
 * as {@value #DEFAULT_RESOURCE} (bundles/sabot.model/pom.xml); it documents each value's source.
 */
public final class RobotDescriptions {

    /** Resource name of the reference robot's description, next to this class (copied from docs/ at build time). */
    public static final String DEFAULT_RESOURCE = "sabot-robot.properties";

    private static final Map<String, String> KEYS = Map.ofEntries(
            Map.entry("robot.name", "free-form name"),
            Map.entry("wheel.radius.m", "wheel radius, metres"),
            Map.entry("track.width.m", "track width, metres"),
            Map.entry("gear.ratio", "gear ratio, motor turns per wheel turn"),
            Map.entry("encoder.lines", "encoder lines per motor turn"),
            Map.entry("encoder.quadrature", "edges per line (4 = quadrature)"),
            Map.entry("motor.noLoadSpeed.rpm", "motor no-load speed, rpm"),
            Map.entry("limit.linearSpeed.mps", "v_max, m/s"),
            Map.entry("limit.linearAcceleration.mps2", "a_max, m/s^2"),
            Map.entry("limit.angularSpeed.radps", "max yaw rate, rad/s"),
            Map.entry("limit.lateralAcceleration.mps2", "max lateral acceleration, m/s^2"),
            Map.entry("control.period.s", "control period, seconds"));

    private RobotDescriptions() {
    }

    /** @return the reference robot (Maxon A-max 32 drive, 7.5 cm wheels), loaded from {@link #DEFAULT_RESOURCE} */
    public static RobotDescription defaults() {
        try (InputStream in = RobotDescriptions.class.getResourceAsStream(DEFAULT_RESOURCE)) {
            if (in == null) {
                throw new IllegalStateException("resource " + DEFAULT_RESOURCE + " is missing from sabot.model");
            }
            return parse(new String(in.readAllBytes(), StandardCharsets.UTF_8));
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    /**
     * @param file a robot-description properties file
     * @return the validated description
     * @throws IOException                       when the file cannot be read
     * @throws InvalidRobotDescriptionException when a key is missing, unknown or malformed, or a value is invalid
     */
    public static RobotDescription load(Path file) throws IOException {
        return parse(Files.readString(file, StandardCharsets.UTF_8));
    }

    /** Parses the properties text; see the class comment for the keys. */
    public static RobotDescription parse(String text) {
        Properties p = new Properties();
        try (Reader r = new StringReader(text)) {
            p.load(r);
        } catch (IOException | IllegalArgumentException e) {
            throw new InvalidRobotDescriptionException(List.of("not a properties file: " + e.getMessage()));
        }
        List<String> problems = new ArrayList<>();
        Set<String> unknown = new TreeSet<>(p.stringPropertyNames());
        unknown.removeAll(KEYS.keySet());
        for (String k : unknown) {
            problems.add("unknown key '" + k + "'");
        }
        for (String k : new TreeSet<>(KEYS.keySet())) {
            if (p.getProperty(k) == null || p.getProperty(k).isBlank()) {
                problems.add("missing key '" + k + "' (" + KEYS.get(k) + ")");
            }
        }
        double wheelRadius = number(p, "wheel.radius.m", problems);
        double track = number(p, "track.width.m", problems);
        double gear = number(p, "gear.ratio", problems);
        int lines = integer(p, "encoder.lines", problems);
        int quadrature = integer(p, "encoder.quadrature", problems);
        double noLoad = number(p, "motor.noLoadSpeed.rpm", problems);
        double vMax = number(p, "limit.linearSpeed.mps", problems);
        double aMax = number(p, "limit.linearAcceleration.mps2", problems);
        double wMax = number(p, "limit.angularSpeed.radps", problems);
        double latMax = number(p, "limit.lateralAcceleration.mps2", problems);
        double period = number(p, "control.period.s", problems);
        if (!problems.isEmpty()) {
            throw new InvalidRobotDescriptionException(problems);
        }
        return new RobotDescription(p.getProperty("robot.name").trim(), wheelRadius, track, gear, lines, quadrature,
                noLoad, vMax, aMax, wMax, latMax, period);
    }

    private static double number(Properties p, String key, List<String> problems) {
        String v = p.getProperty(key);
        if (v == null || v.isBlank()) {
            return Double.NaN;
        }
        try {
            return Double.parseDouble(v.trim());
        } catch (NumberFormatException e) {
            problems.add("key '" + key + "' is not a number: '" + v.trim() + "'");
            return Double.NaN;
        }
    }

    private static int integer(Properties p, String key, List<String> problems) {
        String v = p.getProperty(key);
        if (v == null || v.isBlank()) {
            return 0;
        }
        try {
            return Integer.parseInt(v.trim());
        } catch (NumberFormatException e) {
            problems.add("key '" + key + "' is not an integer: '" + v.trim() + "'");
            return 0;
        }
    }
}
