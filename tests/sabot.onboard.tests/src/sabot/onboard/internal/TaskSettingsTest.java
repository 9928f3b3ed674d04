package sabot.onboard.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;
import java.nio.file.Paths;
import java.util.Hashtable;
import java.util.List;
import java.util.Map;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;
import org.osgi.service.metatype.AttributeDefinition;

class TaskSettingsTest {

    private static final Path FILE = Paths.get("onboard.conf");
    private static final Map<String, Map<String, SettingSpec>> CATALOG = Map.of(
            "heartbeat", Map.of(
                    "period", new SettingSpec("period", AttributeDefinition.INTEGER, 1.0, 3600.0),
                    "warnLoad", new SettingSpec("warnLoad", AttributeDefinition.DOUBLE, 0.0, 1.0),
                    "verbose", new SettingSpec("verbose", AttributeDefinition.BOOLEAN, null, null)),
            "planner", Map.of());

    @Test
    void enabledTasksGetTypedSettingsAndDisabledTasksNone() throws Exception {
        OnboardConfigFile c = OnboardConfigFile.parse(FILE, """
                tasks = heartbeat
                heartbeat.period = 7
                heartbeat.warnLoad = 0.5
                heartbeat.verbose = TRUE
                """);
        Map<String, Hashtable<String, Object>> enabled = TaskSettings.resolve(c, CATALOG);
        assertEquals(List.of("heartbeat"), List.copyOf(enabled.keySet()));
        assertEquals(7, enabled.get("heartbeat").get("period"));
        assertEquals(0.5, enabled.get("heartbeat").get("warnLoad"));
        assertEquals(Boolean.TRUE, enabled.get("heartbeat").get("verbose"));
    }

    @Test
    void settingsOfADisabledTaskAreStillChecked() throws Exception {
        OnboardConfigFile c = OnboardConfigFile.parse(FILE, "tasks = planner\nheartbeat.period = 0\n");
        ConfigError e = assertThrows(ConfigError.class, () -> TaskSettings.resolve(c, CATALOG));
        assertEquals("heartbeat.period", e.key());
    }

    @ParameterizedTest(name = "{0}")
    @CsvSource(delimiter = '|', value = {
        "unknown task          | tasks = heartbeat, mapper      | tasks             | unknown task 'mapper' (available: heartbeat, planner)",
        "unknown section       | tasks = heartbeat\\nmapper.x = 1 | mapper.x          | unknown section 'mapper'",
        "unknown setting       | tasks = heartbeat\\nheartbeat.perod = 5 | heartbeat.perod | task 'heartbeat' has no setting 'perod' (settings: period, verbose, warnLoad)",
        "not an integer        | tasks = heartbeat\\nheartbeat.period = 5s | heartbeat.period | '5s' is not an integer",
        "below the minimum     | tasks = heartbeat\\nheartbeat.period = 0 | heartbeat.period | '0' is below the minimum 1",
        "above the maximum     | tasks = heartbeat\\nheartbeat.period = 3601 | heartbeat.period | '3601' is above the maximum 3600",
        "NaN                   | tasks = heartbeat\\nheartbeat.warnLoad = NaN | heartbeat.warnLoad | 'NaN' is not a finite number",
        "infinite              | tasks = heartbeat\\nheartbeat.warnLoad = Infinity | heartbeat.warnLoad | 'Infinity' is not a finite number",
        "not a boolean         | tasks = heartbeat\\nheartbeat.verbose = yes | heartbeat.verbose | 'yes' is not true or false" })
    void invalidSettingIsRejectedNamingTheKey(String what, String text, String key, String problem) throws Exception {
        OnboardConfigFile c = OnboardConfigFile.parse(FILE, text.replace("\\n", "\n"));
        ConfigError e = assertThrows(ConfigError.class, () -> TaskSettings.resolve(c, CATALOG));
        assertEquals(key, e.key(), e.getMessage());
        assertTrue(e.getMessage().contains(problem), e.getMessage());
    }
}
