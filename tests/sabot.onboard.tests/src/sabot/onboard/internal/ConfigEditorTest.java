package sabot.onboard.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.osgi.service.metatype.AttributeDefinition;

import sabot.onboard.config.SettingForm;
import sabot.onboard.config.SettingsChange;
import sabot.onboard.config.TaskForm;
import sabot.onboard.task.TaskSettingsCheck;

/**
 * The configuration file changed while the robot runs ({@link ConfigEditor}, behind the robot's web page): the same
 * checks and texts as at start, an atomic write that keeps comments and the file's mode, nothing written when refused,
 * and the running task's new configuration handed on.
 */
class ConfigEditorTest {

    private static final Map<String, Map<String, SettingSpec>> CATALOG = Map.of(
            "heartbeat", Map.of(
                    "period", new SettingSpec("period", AttributeDefinition.INTEGER, 1.0, 3600.0),
                    "verbose", new SettingSpec("verbose", AttributeDefinition.BOOLEAN, null, null)),
            "planner", Map.of("map", new SettingSpec("map", AttributeDefinition.STRING, null, null)));

    private static final String TEXT = """
            # the robot
            robot.name = r1
            tasks = heartbeat
            heartbeat.period = 5   # seconds
            """;

    @TempDir
    Path dir;
    private final List<String> applied = new ArrayList<>();

    private ConfigEditor editor(Path file) {
        // a check of what Metatype cannot say: verbose only at short periods
        TaskSettingsCheck chatty = settings -> settings.containsKey("verbose") && settings.get("period") instanceof
                Integer period && period > 100 ? List.of(new TaskSettingsCheck.Problem("verbose",
                        "too chatty at this period")) : List.of();
        return new ConfigEditor(file, "r1", CATALOG, () -> List.of(new TaskForm("heartbeat", "Heartbeat", "", false,
                List.of(new SettingForm("period", "Period", "", "integer", "1", "3600", "10", List.of(), false, null))),
                new TaskForm("planner", "Planner", "", false, List.of())), task -> task.equals("heartbeat") ? List.of(
                        chatty) : List.of(),
                (task, properties) -> applied.add(task + " " + new java.util.TreeMap<>(properties)));
    }

    private Path file() throws Exception {
        Path file = dir.resolve("onboard.conf");
        Files.writeString(file, TEXT);
        Files.setPosixFilePermissions(file, PosixFilePermissions.fromString("rw-r-----"));
        return file;
    }

    @Test
    void aChangeReplacesTheLineKeepsItsCommentAddsNewOnesAndIsApplied() throws Exception {
        Path file = file();
        Map<String, String> values = new LinkedHashMap<>();
        values.put("period", "7");
        values.put("verbose", "true");
        SettingsChange c = editor(file).change("heartbeat", values);
        assertTrue(c.applied(), c.message());
        assertEquals("written to " + file + "; task 'heartbeat' restarts with its new settings", c.message());
        assertEquals("""
                # the robot
                robot.name = r1
                tasks = heartbeat
                heartbeat.period = 7  # seconds
                heartbeat.verbose = true
                """, Files.readString(file));
        assertEquals("rw-r-----", PosixFilePermissions.toString(Files.getPosixFilePermissions(file)));
        assertEquals(List.of("heartbeat {period=7, robot.name=r1, verbose=true}"), applied);
        try (var left = Files.list(dir)) {
            assertEquals(List.of(file), left.toList(), "no temporary file left");
        }
    }

    @Test
    void anEmptyValueRemovesTheSettingSoItsDefaultApplies() throws Exception {
        Path file = file();
        assertTrue(editor(file).change("heartbeat", Map.of("period", "")).applied());
        assertEquals("# the robot\nrobot.name = r1\ntasks = heartbeat\n# seconds\n", Files.readString(file));
        assertEquals(List.of("heartbeat {robot.name=r1}"), applied);
    }

    @Test
    void refusalsCarryTheStartsTextAndWriteNothing() throws Exception {
        Path file = file();
        byte[] before = Files.readAllBytes(file);
        ConfigEditor e = editor(file);
        assertEquals(file + ":4: key 'heartbeat.period': '0' is below the minimum 1", refused(e, "heartbeat", Map.of(
                "period", "0")));
        assertEquals(file + ":4: key 'heartbeat.period': 'x' is not an integer", refused(e, "heartbeat", Map.of(
                "period", "x")));
        assertEquals(file + ":5: key 'heartbeat.bogus': task 'heartbeat' has no setting 'bogus' (settings: period, "
                + "verbose)", refused(e, "heartbeat", Map.of("bogus", "1")));
        assertEquals(file + ":5: key 'heartbeat.verbose': too chatty at this period", refused(e, "heartbeat",
                new LinkedHashMap<>(Map.of("period", "200", "verbose", "true"))));
        assertEquals(file + ": key 'heartbeat.period': a value in this file cannot hold '#' or a line break", refused(
                e, "heartbeat", Map.of("period", "5 # more")));
        assertEquals(file + ": key 'tasks': unknown task 'robot' (available: heartbeat, planner)", refused(e, "robot",
                Map.of("name", "r2")));
        assertTrue(java.util.Arrays.equals(before, Files.readAllBytes(file)), "the file changed");
        assertTrue(applied.isEmpty(), applied.toString());
    }

    @Test
    void aTaskNotRunningIsWrittenNotAppliedAndTheFormsShowTheFilesValues() throws Exception {
        Path file = file();
        ConfigEditor e = editor(file);
        SettingsChange c = e.change("planner", Map.of("map", "/maps/lab.yaml"));
        assertTrue(c.applied(), c.message());
        assertTrue(c.message().contains("task 'planner' is not in 'tasks'"), c.message());
        assertTrue(applied.isEmpty());
        List<TaskForm> forms = e.tasks();
        assertEquals("5", forms.get(0).settings().get(0).value());
        assertTrue(forms.get(0).enabled());
        assertFalse(forms.get(1).enabled());
        assertTrue(Files.readString(file, StandardCharsets.UTF_8).endsWith("planner.map = /maps/lab.yaml\n"));
    }

    private static String refused(ConfigEditor e, String task, Map<String, String> values) {
        SettingsChange c = e.change(task, values);
        assertFalse(c.applied(), c.message());
        return c.message();
    }
}
