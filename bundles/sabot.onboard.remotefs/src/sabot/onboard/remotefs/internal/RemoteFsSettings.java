package sabot.onboard.remotefs.internal;

import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.util.List;
import java.util.Map;

import org.osgi.service.metatype.annotations.AttributeDefinition;
import org.osgi.service.metatype.annotations.ObjectClassDefinition;

import sabot.controlml.payload.FileChunk;
import sabot.onboard.task.SettingsParser;
import sabot.onboard.task.TaskProperties;
import sabot.onboard.task.OnboardTask;
import sabot.onboard.task.TaskSettingsCheck.Problem;

/**
 * The settings of the {@code remotefs} task (declared by {@link Config}): the root directory and the
 * {@link RemoteFsLimits}. Defaults are {@link RemoteFsLimits#DEFAULT}'s.
 *
 * @param root   the directory the remote FS shows (absolute, existing)
 * @param limits the limits and the read-only flag
 */
public record RemoteFsSettings(Path root, RemoteFsLimits limits) {

    /** The task's name. */
    public static final String TASK = "remotefs";

    /**
     * The task's settings: its Metatype description, generated from these annotations. The task reads its
     * configuration through {@link RemoteFsSettings#of}, which checks it again for any other Config Admin client.
     */
    @ObjectClassDefinition(id = OnboardTask.PID_PREFIX + TASK, name = "Remote file system",
            description = "Serves cm.fs.list, cm.fs.read, cm.fs.write and cm.fs.delete on one directory of the robot.")
    public @interface Config {
        @AttributeDefinition(name = "Root directory", description = "The directory the remote FS shows; it must "
                + "exist. Nothing outside it can be read or written.")
        String root();

        @AttributeDefinition(name = "Read-only", description = "true: writes and deletes are refused (forbidden / "
                + "set-not-permitted).")
        boolean readOnly() default false;

        @AttributeDefinition(name = "Largest chunk", description = "Bytes at most in one cm.fs.read answer or "
                + "cm.fs.write chunk (one ControlML payload carries 32 KiB).", min = "1", max = "" + FileChunk.MAX_CHUNK)
        int maxChunk() default FileChunk.MAX_CHUNK;

        @AttributeDefinition(name = "Largest file", description = "Bytes at most in a file written through "
                + "cm.fs.write.", min = "0")
        long maxFileSize() default RemoteFsLimits.DEFAULT_MAX_FILE_SIZE;

        @AttributeDefinition(name = "Listing page", description = "Entries at most in one cm.fs.list answer (fewer "
                + "when long names would not fit one payload).", min = "1", max = "" + RemoteFsLimits.MAX_LIST_PAGE)
        int pageSize() default RemoteFsLimits.DEFAULT_LIST_PAGE;

        @AttributeDefinition(name = "Writes in progress", description = "Writes in progress at once; one more abandons "
                + "the one that waited longest and deletes its temporary file.", min = "1",
                max = "" + RemoteFsLimits.MAX_OPEN_TRANSFERS)
        int maxTransfers() default RemoteFsLimits.DEFAULT_OPEN_TRANSFERS;
    }

    /**
     * @param properties the task's configuration
     * @return the settings
     * @throws sabot.onboard.task.InvalidSettings listing every problem
     */
    public static RemoteFsSettings of(Map<String, ?> properties) {
        return PARSER.of(TASK, properties);
    }

    /** @return the problems of a configuration; empty when {@link #of} would succeed */
    public static List<Problem> problems(Map<String, ?> properties) {
        return PARSER.problems(properties);
    }

    /** The one parse behind {@link #of} and {@link #problems}. */
    private static final SettingsParser<RemoteFsSettings> PARSER = RemoteFsSettings::parse;

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
        long maxTransfers = integer(p, "maxTransfers", d.maxOpenTransfers(), 1, RemoteFsLimits.MAX_OPEN_TRANSFERS,
                problems);
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
