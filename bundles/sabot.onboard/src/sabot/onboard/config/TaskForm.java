package sabot.onboard.config;

import java.util.List;

/**
 * One installed task and its settings, as its Metatype description declares them.
 *
 * @param name        the task's name in the file, e.g. {@code remotefs}; never null
 * @param title       the description's name, e.g. "Remote file system"; never null (the name when it has none)
 * @param description what the task does; never null, may be empty
 * @param enabled     true when the file's {@code tasks} lists it (it runs)
 * @param settings    its settings in declaration order; never null
 */
public record TaskForm(String name, String title, String description, boolean enabled, List<SettingForm> settings) {
    public TaskForm {
        settings = List.copyOf(settings);
    }
}
