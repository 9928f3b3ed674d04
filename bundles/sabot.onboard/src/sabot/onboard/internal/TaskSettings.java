package sabot.onboard.internal;

import java.util.Hashtable;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.TreeSet;

/**
 * Checks a configuration file against the tasks that are installed and the settings each declares, and turns the
 * enabled tasks' settings into typed configuration properties. Nothing is applied unless the whole file is valid.
 */
public final class TaskSettings {

    private TaskSettings() {
    }

    /**
     * @param config  the parsed file
     * @param catalog installed tasks: task name to its settings by id
     * @return the enabled tasks in file order, each with its typed configuration properties
     * @throws ConfigError naming the file, line and key of the first problem
     */
    public static Map<String, Hashtable<String, Object>> resolve(OnboardConfigFile config,
            Map<String, Map<String, SettingSpec>> catalog) throws ConfigError {
        String available = catalog.isEmpty() ? "none installed" : "available: " + String.join(", ",
                new TreeSet<>(catalog.keySet()));
        Map<String, Hashtable<String, Object>> enabled = new LinkedHashMap<>();
        for (String task : config.tasks()) {
            if (!catalog.containsKey(task)) {
                throw new ConfigError(config.file(), config.tasksEntry().line(), OnboardConfigFile.TASKS,
                        "unknown task '" + task + "' (" + available + ")");
            }
            enabled.put(task, new Hashtable<>());
        }
        for (OnboardConfigFile.Entry entry : config.entries().values()) {
            String key = entry.key();
            if (key.equals(OnboardConfigFile.TASKS) || key.equals(OnboardConfigFile.ROBOT_NAME)) {
                continue;
            }
            int dot = key.indexOf('.');
            String task = key.substring(0, dot);
            String setting = key.substring(dot + 1);
            Map<String, SettingSpec> specs = catalog.get(task);
            if (specs == null) {
                throw new ConfigError(config.file(), entry.line(), key, "unknown section '" + task
                        + "': neither 'robot' nor a task (" + available + ")");
            }
            SettingSpec spec = specs.get(setting);
            if (spec == null) {
                throw new ConfigError(config.file(), entry.line(), key, "task '" + task + "' has no setting '"
                        + setting + "' (settings: " + String.join(", ", new TreeSet<>(specs.keySet())) + ")");
            }
            Object value;
            try {
                value = spec.convert(entry.value());
            } catch (IllegalArgumentException bad) {
                throw new ConfigError(config.file(), entry.line(), key, bad.getMessage());
            }
            Hashtable<String, Object> props = enabled.get(task);
            if (props != null) {
                props.put(setting, value);
            }
        }
        return enabled;
    }
}
