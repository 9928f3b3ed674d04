package sabot.onboard.internal;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.AtomicMoveNotSupportedException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.StandardCopyOption;
import java.util.ArrayList;
import java.util.Hashtable;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.function.Function;
import java.util.function.Supplier;

import sabot.onboard.config.OnboardSettings;
import sabot.onboard.config.SettingsChange;
import sabot.onboard.config.TaskForm;
import sabot.onboard.task.OnboardTask;
import sabot.onboard.task.TaskSettingsCheck;

/**
 * {@link OnboardSettings} over the configuration file: a change is made on the file's text, checked whole with
 * {@link OnboardConfigFile#parse}, {@link TaskSettings#resolve} and {@link TaskSettings#check} (the start's rules and
 * texts), written atomically and handed to the task's configuration ({@link Apply}). Free of OSGi, so that a plain test
 * drives it on a file and a catalogue of its own.
 */
final class ConfigEditor implements OnboardSettings {

    /** Applies a running task's new configuration (Config Admin in the product). */
    @FunctionalInterface
    interface Apply {
        void configure(String task, Hashtable<String, Object> properties) throws IOException;
    }

    private final Path file;
    private final String robotName;
    private final Map<String, Map<String, SettingSpec>> catalog;
    private final Supplier<List<TaskForm>> forms;
    private final Function<String, List<TaskSettingsCheck>> checks;
    private final Apply apply;

    /**
     * @param catalog the installed tasks' settings (as at start)
     * @param forms   the forms of every installed task, without values
     * @param checks  the {@link TaskSettingsCheck}s of a task
     * @param apply   applies a running task's new configuration
     */
    ConfigEditor(Path file, String robotName, Map<String, Map<String, SettingSpec>> catalog,
            Supplier<List<TaskForm>> forms, Function<String, List<TaskSettingsCheck>> checks, Apply apply) {
        this.file = file;
        this.robotName = robotName;
        this.catalog = catalog;
        this.forms = forms;
        this.checks = checks;
        this.apply = apply;
    }

    @Override
    public Path file() {
        return file;
    }

    @Override
    public String robotName() {
        return robotName;
    }

    @Override
    public synchronized List<TaskForm> tasks() {
        OnboardConfigFile config;
        List<String> enabled;
        try {
            config = OnboardConfigFile.read(file);
            enabled = config.tasks();
        } catch (ConfigError e) {
            config = null;
            enabled = List.of();
        }
        List<TaskForm> result = new ArrayList<>();
        for (TaskForm blank : forms.get()) {
            Map<String, OnboardConfigFile.Entry> values = config == null ? Map.of() : config.settingsOf(blank.name());
            result.add(new TaskForm(blank.name(), blank.title(), blank.description(), enabled.contains(blank.name()),
                    blank.settings().stream().map(s -> {
                        OnboardConfigFile.Entry e = values.get(s.id());
                        return new sabot.onboard.config.SettingForm(s.id(), s.name(), s.description(), s.type(), s
                                .min(), s.max(), s.defaultValue(), s.options(), s.mandatory(), e == null ? null : e
                                        .value());
                    }).toList()));
        }
        return result;
    }

    @Override
    public synchronized SettingsChange change(String task, Map<String, String> values) {
        if (!catalog.containsKey(task)) {
            return new SettingsChange(false, new ConfigError(file, 0, OnboardConfigFile.TASKS, "unknown task '" + task
                    + "' (available: " + String.join(", ", new java.util.TreeSet<>(catalog.keySet())) + ")")
                    .getMessage());
        }
        String text;
        OnboardConfigFile before;
        try {
            before = OnboardConfigFile.read(file);
            text = Files.readString(file, StandardCharsets.UTF_8);
        } catch (ConfigError e) {
            return new SettingsChange(false, e.getMessage());
        } catch (IOException e) {
            return new SettingsChange(false, new ConfigError(file, 0, null, "cannot read: " + e.getMessage())
                    .getMessage());
        }
        String edited;
        try {
            edited = edit(file, text, before, task, values);
        } catch (ConfigError e) {
            return new SettingsChange(false, e.getMessage());
        }
        Map<String, Hashtable<String, Object>> enabled;
        OnboardConfigFile after;
        try {
            after = OnboardConfigFile.parse(file, edited);
            enabled = TaskSettings.resolve(after, catalog);
            TaskSettings.check(after, enabled, checks);
        } catch (ConfigError e) {
            return new SettingsChange(false, e.getMessage());
        }
        if (edited.equals(text)) {
            return new SettingsChange(true, "nothing changed in " + file);
        }
        try {
            writeAtomically(file, edited);
        } catch (IOException e) {
            return new SettingsChange(false, new ConfigError(file, 0, null, "cannot write: " + e.getMessage())
                    .getMessage());
        }
        Hashtable<String, Object> properties = enabled.get(task);
        if (properties == null) {
            return new SettingsChange(true, "written to " + file + "; task '" + task + "' is not in '"
                    + OnboardConfigFile.TASKS + "', so it takes these settings once it is listed there and the robot "
                    + "restarts");
        }
        properties.put(OnboardTask.ROBOT_NAME, robotName);
        try {
            apply.configure(task, properties);
        } catch (IOException e) {
            return new SettingsChange(true, "written to " + file + ", but not applied (" + e.getMessage()
                    + "): the task takes them when the robot restarts");
        }
        return new SettingsChange(true, "written to " + file + "; task '" + task + "' restarts with its new settings");
    }

    /**
     * @return {@code text} with the task's settings set (a line replaced in place, its comment kept) or added at the
     *         end, or removed for an empty value
     * @throws ConfigError for a value the file's syntax cannot hold, or a task name that is not one
     */
    static String edit(Path file, String text, OnboardConfigFile config, String task, Map<String, String> values)
            throws ConfigError {
        if (task == null || !task.matches("[a-z][a-z0-9_-]*")) {
            throw new ConfigError(file, 0, OnboardConfigFile.TASKS, "'" + task + "' is not a task name");
        }
        List<String> lines = new ArrayList<>(List.of(text.split("\\R", -1)));
        boolean endsWithNewline = !lines.isEmpty() && lines.get(lines.size() - 1).isEmpty();
        if (endsWithNewline) {
            lines.remove(lines.size() - 1);
        }
        Map<Integer, String> replaced = new LinkedHashMap<>();
        List<String> added = new ArrayList<>();
        for (Map.Entry<String, String> v : values.entrySet()) {
            String key = task + "." + v.getKey();
            String value = v.getValue() == null ? "" : v.getValue().strip();
            if (value.indexOf('#') >= 0 || value.indexOf('\n') >= 0 || value.indexOf('\r') >= 0) {
                throw new ConfigError(file, 0, key, "a value in this file cannot hold '#' or a line break");
            }
            OnboardConfigFile.Entry existing = config.entries().get(key);
            String line = value.isEmpty() ? null : key + " = " + value;
            if (existing != null) {
                String old = lines.get(existing.line() - 1);
                int hash = old.indexOf('#');
                replaced.put(existing.line() - 1, line == null ? (hash < 0 ? null : old.substring(hash))
                        : hash < 0 ? line : line + "  " + old.substring(hash));
            } else if (line != null) {
                added.add(line);
            }
        }
        List<String> out = new ArrayList<>();
        for (int i = 0; i < lines.size(); i++) {
            if (replaced.containsKey(i)) {
                String line = replaced.get(i);
                if (line != null) {
                    out.add(line);
                }
            } else {
                out.add(lines.get(i));
            }
        }
        out.addAll(added);
        return String.join("\n", out) + "\n";
    }

    /** A temporary file beside {@code file}, with its permissions, renamed over it: a reader sees the old or the new. */
    static void writeAtomically(Path file, String text) throws IOException {
        Path dir = file.toAbsolutePath().getParent();
        Path temp = Files.createTempFile(dir, "." + file.getFileName() + ".", ".tmp");
        try {
            try {
                Files.setPosixFilePermissions(temp, Files.getPosixFilePermissions(file));
            } catch (UnsupportedOperationException notPosix) {
                // the temporary file keeps its own (owner only)
            }
            Files.writeString(temp, text, StandardCharsets.UTF_8);
            try (var channel = java.nio.channels.FileChannel.open(temp, java.nio.file.StandardOpenOption.WRITE)) {
                channel.force(true);
            }
            try {
                Files.move(temp, file, StandardCopyOption.ATOMIC_MOVE, StandardCopyOption.REPLACE_EXISTING);
            } catch (AtomicMoveNotSupportedException e) {
                throw new IOException("cannot replace " + file + " atomically: " + e.getMessage(), e);
            }
        } finally {
            Files.deleteIfExists(temp);
        }
    }
}
