package sabot.onboard.task;

import java.util.ArrayList;
import java.util.List;
import java.util.Map;

import org.osgi.annotation.versioning.ConsumerType;

import sabot.onboard.task.TaskSettingsCheck.Problem;

/**
 * How a task reads its configuration into its settings: one parse that lists every problem, from which both the
 * component's start ({@link #of}: the settings, or {@link InvalidSettings}) and the task's {@link TaskSettingsCheck}
 * ({@link #problems}) are made, so that the two never disagree.
 *
 * @param <S> the task's settings
 * @since 0.3
 */
@ConsumerType
@FunctionalInterface
public interface SettingsParser<S> {

    /**
     * @param properties the task's configuration
     * @param problems   where each problem is added, in the order found
     * @return the settings, or null when a problem was added
     */
    S parse(Map<String, ?> properties, List<Problem> problems);

    /**
     * @param task       the task's name, for the exception's text
     * @param properties the task's configuration
     * @return the settings
     * @throws InvalidSettings listing every problem
     */
    default S of(String task, Map<String, ?> properties) {
        List<Problem> problems = new ArrayList<>();
        S settings = parse(properties, problems);
        if (settings == null || !problems.isEmpty()) {
            throw new InvalidSettings(task, problems);
        }
        return settings;
    }

    /** @return the problems of a configuration, in the order found; empty when {@link #of} succeeds */
    default List<Problem> problems(Map<String, ?> properties) {
        List<Problem> problems = new ArrayList<>();
        parse(properties, problems);
        return problems;
    }
}
