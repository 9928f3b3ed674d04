package sabot.onboard.internal;

import java.io.IOException;
import java.nio.charset.CharacterCodingException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Collections;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * The onboard configuration file, parsed strictly: one {@code key = value} per line, {@code #} starts a comment,
 * keys are lower-case dotted names, each key at most once. Global keys are {@link #ROBOT_NAME} and {@link #TASKS};
 * every other key is {@code <task>.<setting>} and is checked later against the task's declared settings.
 */
public final class OnboardConfigFile {

    public static final String ROBOT_NAME = "robot.name";
    public static final String TASKS = "tasks";

    private static final Pattern LINE = Pattern.compile("^\\s*([^=\\s]+)\\s*=\\s*(.*?)\\s*$");
    private static final Pattern KEY = Pattern.compile("[a-z][a-z0-9_-]*(\\.[a-zA-Z][a-zA-Z0-9_-]*)+|tasks");
    private static final Pattern TASK_NAME = Pattern.compile("[a-z][a-z0-9_-]*");

    /** A value and the line it was written on. */
    public record Entry(String key, String value, int line) {
    }

    private final Path file;
    private final Map<String, Entry> entries;

    private OnboardConfigFile(Path file, Map<String, Entry> entries) {
        this.file = file;
        this.entries = entries;
    }

    /** Reads and parses a configuration file; every problem names the file, the line and the key. */
    public static OnboardConfigFile read(Path file) throws ConfigError {
        String text;
        try {
            text = StandardCharsets.UTF_8.newDecoder().decode(java.nio.ByteBuffer.wrap(Files.readAllBytes(file)))
                    .toString();
        } catch (NoSuchFileException e) {
            throw new ConfigError(file, 0, null, "file not found");
        } catch (CharacterCodingException e) {
            throw new ConfigError(file, 0, null, "not UTF-8 text");
        } catch (IOException e) {
            throw new ConfigError(file, 0, null, "cannot read: " + e.getMessage());
        }
        return parse(file, text);
    }

    /** Parses configuration text; {@code file} is only used in error messages. */
    public static OnboardConfigFile parse(Path file, String text) throws ConfigError {
        Map<String, Entry> entries = new LinkedHashMap<>();
        String[] lines = text.split("\\R", -1);
        for (int i = 0; i < lines.length; i++) {
            int lineNo = i + 1;
            String line = stripComment(lines[i]);
            if (line.isBlank()) {
                continue;
            }
            Matcher m = LINE.matcher(line);
            if (!m.matches()) {
                throw new ConfigError(file, lineNo, null, "expected 'key = value', found '" + line.strip() + "'");
            }
            String key = m.group(1);
            String value = m.group(2);
            if (!KEY.matcher(key).matches()) {
                throw new ConfigError(file, lineNo, key, "not a valid key (lower-case '<section>.<name>' expected)");
            }
            Entry previous = entries.putIfAbsent(key, new Entry(key, value, lineNo));
            if (previous != null) {
                throw new ConfigError(file, lineNo, key, "set twice (first on line " + previous.line() + ")");
            }
            if (key.startsWith("robot.") && !key.equals(ROBOT_NAME)) {
                throw new ConfigError(file, lineNo, key, "unknown key (the robot section has only '" + ROBOT_NAME
                        + "')");
            }
        }
        OnboardConfigFile config = new OnboardConfigFile(file, Collections.unmodifiableMap(entries));
        config.tasks(); // validates the task list syntax early
        return config;
    }

    private static String stripComment(String line) {
        int hash = line.indexOf('#');
        return hash < 0 ? line : line.substring(0, hash);
    }

    public Path file() {
        return file;
    }

    /** @return the robot's name, or {@code defaultName} when the file does not set one */
    public String robotName(String defaultName) {
        Entry e = entries.get(ROBOT_NAME);
        return e == null || e.value().isEmpty() ? defaultName : e.value();
    }

    /** @return the enabled task names in file order; empty when {@code tasks} is absent or empty */
    public List<String> tasks() throws ConfigError {
        Entry e = entries.get(TASKS);
        if (e == null || e.value().isBlank()) {
            return List.of();
        }
        List<String> names = new ArrayList<>();
        for (String raw : e.value().split(",")) {
            String name = raw.strip();
            if (!TASK_NAME.matcher(name).matches()) {
                throw new ConfigError(file, e.line(), TASKS, "'" + name + "' is not a task name");
            }
            if (names.contains(name)) {
                throw new ConfigError(file, e.line(), TASKS, "task '" + name + "' listed twice");
            }
            names.add(name);
        }
        return List.copyOf(names);
    }

    /** @return the entry that holds {@link #TASKS}, or null */
    public Entry tasksEntry() {
        return entries.get(TASKS);
    }

    /** @return the settings of one task: setting id to entry, in file order */
    public Map<String, Entry> settingsOf(String task) {
        Map<String, Entry> settings = new LinkedHashMap<>();
        String prefix = task + ".";
        entries.forEach((key, entry) -> {
            if (key.startsWith(prefix)) {
                settings.put(key.substring(prefix.length()), entry);
            }
        });
        return settings;
    }

    /** @return every entry in file order */
    public Map<String, Entry> entries() {
        return entries;
    }
}
