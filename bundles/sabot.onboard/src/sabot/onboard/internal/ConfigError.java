package sabot.onboard.internal;

import java.nio.file.Path;

/**
 * A problem in the onboard configuration file, located precisely enough for an operator to fix it: the file, the
 * line (0 when the problem is not on one line) and the key.
 */
public final class ConfigError extends Exception {

    private static final long serialVersionUID = 1L;

    private final Path file;
    private final int line;
    private final String key;

    public ConfigError(Path file, int line, String key, String problem) {
        super(format(file, line, key, problem));
        this.file = file;
        this.line = line;
        this.key = key;
    }

    private static String format(Path file, int line, String key, String problem) {
        StringBuilder sb = new StringBuilder().append(file);
        if (line > 0) {
            sb.append(':').append(line);
        }
        sb.append(": ");
        if (key != null) {
            sb.append("key '").append(key).append("': ");
        }
        return sb.append(problem).toString();
    }

    public Path file() {
        return file;
    }

    /** @return the 1-based line number, or 0 when the problem concerns the whole file */
    public int line() {
        return line;
    }

    /** @return the offending key, or null when the problem is not tied to a key */
    public String key() {
        return key;
    }
}
