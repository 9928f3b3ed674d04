package sabot.onboard.config;

import java.util.Objects;

/**
 * The outcome of {@link OnboardSettings#change}.
 *
 * @param applied true when the file was written (and the task's configuration updated when it runs)
 * @param message applied: what happened, e.g. that the task restarted with its new settings or that it takes them
 *                when enabled; refused: the configuration error, as the product prints it at start; never null
 */
public record SettingsChange(boolean applied, String message) {
    public SettingsChange {
        Objects.requireNonNull(message, "message");
    }
}
