package sabot.onboard.motion.internal;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;

import org.osgi.service.component.annotations.Component;

import sabot.model.map.MapServerFormat;
import sabot.onboard.motion.loop.LoopDefaults;
import sabot.onboard.task.TaskSettingsCheck;

/**
 * What Metatype cannot say about the motion tasks' settings, checked before anything starts: the bus's serial device
 * must exist (or a TCP gateway be named), the planner's map (with the landmarks and docks it names) must load, and the
 * battery's low threshold must lie below its charged one.
 */
final class MotionSettingsChecks {

    private MotionSettingsChecks() {
    }

    /** {@code bus}: a serial device that exists, or a TCP host; not both, not neither. */
    @Component(service = TaskSettingsCheck.class, property = TaskSettingsCheck.TASK + "=bus")
    public static final class Bus implements TaskSettingsCheck {
        @Override
        public List<Problem> check(Map<String, Object> settings) {
            String port = (String) settings.getOrDefault("port", "");
            String host = (String) settings.getOrDefault("tcpHost", "");
            List<Problem> problems = new ArrayList<>();
            if (port.isBlank() && host.isBlank()) {
                problems.add(new Problem("port", "give the serial device of the RS-485 line (e.g. /dev/ttyUSB0), "
                        + "or bus.tcpHost for an RTU-over-TCP gateway"));
            } else if (!port.isBlank() && !host.isBlank()) {
                problems.add(new Problem("tcpHost", "give either bus.port or bus.tcpHost, not both"));
            } else if (!port.isBlank() && !Files.exists(Path.of(port))) {
                problems.add(new Problem("port", "serial device " + port + " does not exist (is the adapter plugged "
                        + "in, or the simulator running?)"));
            }
            return problems;
        }
    }

    /** {@code planner}: the map must be a readable ROS map_server YAML whose image and landmarks file load. */
    @Component(service = TaskSettingsCheck.class, property = TaskSettingsCheck.TASK + "=planner")
    public static final class Planner implements TaskSettingsCheck {
        @Override
        public List<Problem> check(Map<String, Object> settings) {
            Object map = settings.get("map");
            if (map == null) {
                return List.of(); // a missing mandatory setting is reported by the application
            }
            Path file = Path.of((String) map);
            if (!Files.isRegularFile(file)) {
                return List.of(new Problem("map", "map file " + file + " does not exist"));
            }
            try {
                MapServerFormat.load(file);
                MapServerFormat.readLandmarks(file);
                MapServerFormat.readDocks(file);
                return List.of();
            } catch (IOException | RuntimeException e) {
                return List.of(new Problem("map", "map " + file + " does not load: " + e.getMessage()));
            }
        }
    }

    /** {@code motion}: {@code batteryLow} below {@code batteryCharged}, or a charged robot would be low at once. */
    @Component(service = TaskSettingsCheck.class, property = TaskSettingsCheck.TASK + "=motion")
    public static final class Motion implements TaskSettingsCheck {
        @Override
        public List<Problem> check(Map<String, Object> settings) {
            double low = number(settings.get("batteryLow"), LoopDefaults.BATTERY_LOW);
            double charged = number(settings.get("batteryCharged"), LoopDefaults.BATTERY_CHARGED);
            if (low < charged || Double.isNaN(low) || Double.isNaN(charged)) {
                return List.of();
            }
            return List.of(new Problem("batteryLow", "motion.batteryLow (" + low + ") must be below "
                    + "motion.batteryCharged (" + charged + "): a robot charged to " + charged + " would be low at once"));
        }

        /** A setting as Config Admin holds it (a number, or the file's text), or its default; NaN when not a number. */
        private static double number(Object value, double otherwise) {
            if (value == null) {
                return otherwise;
            }
            if (value instanceof Number n) {
                return n.doubleValue();
            }
            try {
                return Double.parseDouble(value.toString().strip());
            } catch (NumberFormatException e) {
                return Double.NaN; // Metatype reports a malformed number; this check then holds its tongue
            }
        }
    }
}
