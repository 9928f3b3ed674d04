package sabot.onboard.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.util.List;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

class OnboardConfigFileTest {

    private static final Path FILE = Paths.get("/etc/sabot/onboard.conf");

    @Test
    void readsRobotNameTasksAndSettingsIgnoringComments() throws Exception {
        OnboardConfigFile c = OnboardConfigFile.parse(FILE, """
                # Sabot Onboard
                robot.name = sabot-01   # trailing comment
                tasks = heartbeat, planner

                heartbeat.period = 5
                """);
        assertEquals("sabot-01", c.robotName("x"));
        assertEquals(List.of("heartbeat", "planner"), c.tasks());
        assertEquals("5", c.settingsOf("heartbeat").get("period").value());
        assertEquals(5, c.settingsOf("heartbeat").get("period").line());
    }

    @Test
    void emptyFileEnablesNoTask() throws Exception {
        OnboardConfigFile c = OnboardConfigFile.parse(FILE, "\n# nothing\n");
        assertEquals(List.of(), c.tasks());
        assertEquals("unnamed", c.robotName("unnamed"));
    }

    @ParameterizedTest(name = "{0}")
    @CsvSource(delimiter = '|', value = {
        "line without equals sign   | tasks = heartbeat\\nheartbeat period 5 | 2 |                  | expected 'key = value'",
        "key set twice              | tasks = a\\ntasks = b                  | 2 | tasks            | set twice (first on line 1)",
        "upper-case key             | Tasks = a                             | 1 | Tasks            | not a valid key",
        "unknown robot key          | robot.nam = x                         | 1 | robot.nam        | unknown key",
        "bad task name              | tasks = heart beat                    | 1 | tasks            | 'heart beat' is not a task name",
        "task listed twice          | tasks = a, a                          | 1 | tasks            | task 'a' listed twice",
        "key without section        | period = 5                            | 1 | period           | not a valid key" })
    void malformedFileIsRejectedNamingLineAndKey(String what, String text, int line, String key, String problem) {
        ConfigError e = assertThrows(ConfigError.class, () -> OnboardConfigFile.parse(FILE, text.replace("\\n", "\n")));
        assertEquals(line, e.line(), e.getMessage());
        assertEquals(key, e.key(), e.getMessage());
        assertEquals(true, e.getMessage().startsWith(FILE + ":" + line + ": "), e.getMessage());
        assertEquals(true, e.getMessage().contains(problem), e.getMessage());
    }

    @Test
    void missingFileIsReportedWithItsPath(@TempDir Path dir) {
        Path missing = dir.resolve("nope.conf");
        ConfigError e = assertThrows(ConfigError.class, () -> OnboardConfigFile.read(missing));
        assertEquals(missing + ": file not found", e.getMessage());
    }

    @Test
    void binaryFileIsRejected(@TempDir Path dir) throws IOException {
        Path bin = dir.resolve("onboard.conf");
        Files.write(bin, new byte[] { 't', 'a', (byte) 0xC3, (byte) 0x28 });
        ConfigError e = assertThrows(ConfigError.class, () -> OnboardConfigFile.read(bin));
        assertEquals(bin + ": not UTF-8 text", e.getMessage());
    }
}
