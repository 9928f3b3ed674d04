package sabot.onboard.config;

import java.nio.file.Path;
import java.util.List;
import java.util.Map;

import org.osgi.annotation.versioning.ProviderType;

/**
 * The onboard configuration file ({@code etc/onboard.conf} or the file named at start) of the running product. Thread
 * safe: changes are serialised, and each reads the file afresh, so an edit by hand between two changes is kept.
 */
@ProviderType
public interface OnboardSettings {

    /** @return the configuration file (absolute); never null */
    Path file();

    /** @return the robot's name as the file set it at start ({@code robot.name}); never null */
    String robotName();

    /**
     * @return every installed task (enabled or not), sorted by name, with its settings as its Metatype describes them
     *         and their values as the file sets them now; never null
     */
    List<TaskForm> tasks();

    /**
     * Changes settings of one task: the file's text with these values is checked as the product checks it at start
     * (syntax, the task's Metatype types, ranges and options, its {@code TaskSettingsCheck}s, and the rest of the file),
     * then written atomically (a temporary file beside it, renamed over it) and, when the task is enabled, applied
     * through Config Admin: Declarative Services restarts the task with its new settings.
     *
     * @param task   the task's name, e.g. {@code heartbeat}
     * @param values setting id to its text as it would stand in the file; an empty text removes the setting from the
     *               file (the task's default applies). Settings not named keep their lines.
     * @return what happened: applied (with a note for the person who asked), or refused with the error text the
     *         product would print at start for the same file ({@code FILE:LINE: key 'task.setting': problem}), the
     *         file unchanged; never null
     */
    SettingsChange change(String task, Map<String, String> values);
}
