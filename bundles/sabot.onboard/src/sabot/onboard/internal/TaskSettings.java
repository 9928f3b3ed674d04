package sabot.onboard.internal;

import java.util.Collections;
import java.util.Hashtable;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.TreeSet;
import java.util.function.Function;

import sabot.onboard.task.TaskSettingsCheck;

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
        for (Map.Entry<String, Hashtable<String, Object>> task : enabled.entrySet()) {
            for (SettingSpec spec : catalog.get(task.getKey()).values()) {
                if (spec.mandatory() && !task.getValue().containsKey(spec.id())) {
                    throw new ConfigError(config.file(), config.tasksEntry().line(), task.getKey() + "." + spec.id(),
                            "task '" + task.getKey() + "' needs this setting (it has no default)");
                }
            }
        }
        return enabled;
    }

    /**
     * Runs the {@link TaskSettingsCheck}s of every enabled task on its settings; the first problem becomes the error.
     *
     * @param config  the parsed file (for the lines of the keys)
     * @param enabled the result of {@link #resolve}
     * @param checks  the checks of a task, by task name (none: an empty list)
     * @throws ConfigError naming the key of the first problem, at its line (the {@code tasks} line when the file does
     *                     not set the key)
     */
    public static void check(OnboardConfigFile config, Map<String, Hashtable<String, Object>> enabled,
            Function<String, List<TaskSettingsCheck>> checks) throws ConfigError {
        for (Map.Entry<String, Hashtable<String, Object>> task : enabled.entrySet()) {
            Map<String, Object> settings = Collections.unmodifiableMap(new LinkedHashMap<>(task.getValue()));
            for (TaskSettingsCheck check : checks.apply(task.getKey())) {
                List<TaskSettingsCheck.Problem> problems = check.check(settings);
                if (!problems.isEmpty()) {
                    TaskSettingsCheck.Problem first = problems.get(0);
                    String key = task.getKey() + "." + first.setting();
                    OnboardConfigFile.Entry entry = config.entries().get(key);
                    int line = entry != null ? entry.line() : config.tasksEntry().line();
                    throw new ConfigError(config.file(), line, key, first.message());
                }
            }
        }
    }
}
