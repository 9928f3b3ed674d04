package sabot.onboard.internal.remotefs;

import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;

import sabot.controlml.payload.FileChunk;
import sabot.onboard.internal.InvalidSettings;
import sabot.onboard.internal.TaskProperties;
import sabot.onboard.task.TaskSettingsCheck.Problem;

/**
 * The settings of the {@code remotefs} task (OSGI-INF/metatype/remotefs.xml): the root directory and the
 * {@link RemoteFsLimits}. Defaults are {@link RemoteFsLimits#DEFAULT}'s (a test checks the Metatype says the same).
 *
 * @param root   the directory the remote FS shows (absolute, existing)
 * @param limits the limits and the read-only flag
 */
public record RemoteFsSettings(Path root, RemoteFsLimits limits) {

    /** The task's name. */
    public static final String TASK = "remotefs";

    /**
     * @param properties the task's configuration
     * @return the settings
     * @throws InvalidSettings listing every problem
     */
    public static RemoteFsSettings of(Map<String, ?> properties) {
        List<Problem> problems = new ArrayList<>();
        RemoteFsSettings settings = parse(properties, problems);
        if (settings == null) {
            throw new InvalidSettings(TASK, problems);
        }
        return settings;
    }

    /** @return the problems of a configuration; empty when {@link #of} would succeed */
    public static List<Problem> problems(Map<String, ?> properties) {
        List<Problem> problems = new ArrayList<>();
        parse(properties, problems);
        return problems;
    }

    private static RemoteFsSettings parse(Map<String, ?> properties, List<Problem> problems) {
        TaskProperties p = new TaskProperties(properties);
        RemoteFsLimits d = RemoteFsLimits.DEFAULT;
        Path root = null;
        if (!p.has("root")) {
            problems.add(new Problem("root", "no root directory given"));
        } else {
            root = Paths.get(p.string("root", "")).toAbsolutePath().normalize();
            if (!Files.exists(root)) {
                problems.add(new Problem("root", "directory " + root + " does not exist"));
            } else if (!Files.isDirectory(root)) {
                problems.add(new Problem("root", root + " is not a directory"));
            } else if (!Files.isReadable(root) || !Files.isExecutable(root)) {
                problems.add(new Problem("root", "directory " + root + " is not readable by this process (user "
                        + System.getProperty("user.name") + ")"));
            }
        }
        long maxChunk = integer(p, "maxChunk", d.maxChunk(), 1, FileChunk.MAX_CHUNK, problems);
        long maxFileSize = integer(p, "maxFileSize", d.maxFileSize(), 0, Long.MAX_VALUE, problems);
        long pageSize = integer(p, "pageSize", d.maxListPage(), 1, RemoteFsLimits.MAX_LIST_PAGE, problems);
        long maxTransfers = integer(p, "maxTransfers", d.maxOpenTransfers(), 1, Integer.MAX_VALUE, problems);
        boolean readOnly = d.readOnly();
        try {
            readOnly = p.bool("readOnly", d.readOnly());
        } catch (IllegalArgumentException e) {
            problems.add(new Problem("readOnly", e.getMessage()));
        }
        if (!problems.isEmpty()) {
            return null;
        }
        return new RemoteFsSettings(root, new RemoteFsLimits((int) maxChunk, maxFileSize, (int) pageSize,
                (int) maxTransfers, readOnly));
    }

    private static long integer(TaskProperties p, String key, long fallback, long min, long max,
            List<Problem> problems) {
        try {
            long v = p.integer(key, fallback);
            if (v < min || v > max) {
                problems.add(new Problem(key, "'" + v + "' is outside " + min + ".." + max));
            }
            return v;
        } catch (IllegalArgumentException e) {
            problems.add(new Problem(key, e.getMessage()));
            return fallback;
        }
    }
}
