package sabot.controlml.payload;

import java.util.Objects;

/**
 * One task loaded on the robot: a task is provided by a bundle of the onboard product (one bundle may provide several).
 *
 * @param name    the task's name as the configuration file writes it, e.g. {@code planner}; never null
 * @param bundle  the symbolic name of the bundle that provides it, e.g. {@code sabot.onboard.motion}; never null
 * @param version that bundle's version; never null
 * @param state   {@code installed}, {@code resolved}, {@code active} or {@code stopping}; never null
 */
public record TaskInfo(String name, String bundle, String version, String state) {
    public TaskInfo {
        Objects.requireNonNull(name, "name");
        Objects.requireNonNull(bundle, "bundle");
        Objects.requireNonNull(version, "version");
        Objects.requireNonNull(state, "state");
    }
}
