package sabot.controlml.payload;

import java.util.Objects;

/**
 * One task loaded on the robot (a bundle of the onboard runtime).
 *
 * @param name    task name (its symbolic name); never null
 * @param version its version; never null
 * @param state   {@code installed}, {@code resolved}, {@code active} or {@code stopping}; never null
 */
public record TaskInfo(String name, String version, String state) {
    public TaskInfo {
        Objects.requireNonNull(name, "name");
        Objects.requireNonNull(version, "version");
        Objects.requireNonNull(state, "state");
    }
}
