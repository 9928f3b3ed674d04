package sabot.onboard.task;

import java.util.List;
import java.util.Map;
import java.util.Objects;

import org.osgi.annotation.versioning.ConsumerType;

/**
 * Checks of a task's settings that its Metatype description cannot express: a file that must exist with certain
 * permissions, a device that must be present, a value whose syntax is richer than a type and a range.
 * <p>
 * A bundle registers an implementation as an OSGi service with the property {@link #TASK} naming the task (e.g.
 * {@code controlml}). Before anything starts, the onboard application calls the checks of every enabled task with the
 * task's settings as read from the configuration file; any problem stops the product with one line
 * {@code configuration error: FILE:LINE: key '<task>.<setting>': <message>} and exit status 2. A check must be quick,
 * must not touch the network and must change nothing.
 */
@FunctionalInterface
@ConsumerType
public interface TaskSettingsCheck {

    /** Service property: the name of the task whose settings this service checks, e.g. {@code controlml}. */
    String TASK = "sabot.task";

    /**
     * One problem with one setting.
     *
     * @param setting the setting's id within the task, e.g. {@code passwordFile}; never null
     * @param message what is wrong and, where possible, how to fix it; never null
     */
    record Problem(String setting, String message) {
        public Problem {
            Objects.requireNonNull(setting, "setting");
            Objects.requireNonNull(message, "message");
        }
    }

    /**
     * @param settings the task's settings by id as written in the file, already converted to the Metatype types
     *                 ({@code String}, {@code Integer}, {@code Long}, {@code Double}, {@code Boolean}); settings absent
     *                 from the file are absent here (the task applies its defaults); never null
     * @return the problems found, in the order an operator should fix them; empty when the settings are fine
     */
    List<Problem> check(Map<String, Object> settings);
}
