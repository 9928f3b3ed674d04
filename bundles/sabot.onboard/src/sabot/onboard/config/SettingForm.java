package sabot.onboard.config;

import java.util.List;

/**
 * One setting of a task, as its Metatype description declares it, and its value in the file.
 *
 * @param id          the setting's id (after {@code <task>.} in the file); never null
 * @param name        its human name; never null (the id when it has none)
 * @param description what it does, its unit; never null, may be empty
 * @param type        {@code string}, {@code integer}, {@code long}, {@code double}, {@code float} or {@code boolean}
 * @param min         the inclusive lower bound as declared (numbers), or null
 * @param max         the inclusive upper bound as declared (numbers), or null
 * @param defaultValue the default as declared, or null when it has none
 * @param options     the values it may take with their labels; empty: any value of its type and bounds
 * @param mandatory   true when the file must set it (required, no default)
 * @param value       its text in the file now, or null when the file leaves it out (the default applies)
 */
public record SettingForm(String id, String name, String description, String type, String min, String max,
        String defaultValue, List<Option> options, boolean mandatory, String value) {

    public SettingForm {
        options = List.copyOf(options);
    }

    /**
     * @param value the text as written in the file; never null
     * @param label its human label; never null
     */
    public record Option(String value, String label) {
    }
}
