package sabot.onboard.task;

import java.util.List;
import java.util.stream.Collectors;

import sabot.onboard.task.TaskSettingsCheck;

/**
 * A task's configuration, as Declarative Services handed it to the component, is not usable: thrown from the
 * activate method, so SCR logs it and the task does not start. The onboard application finds the same problems
 * earlier, through the task's {@link TaskSettingsCheck}; this covers configurations made by other Config Admin clients.
 */
public final class InvalidSettings extends IllegalArgumentException {

    private static final long serialVersionUID = 1L;

    private final transient List<TaskSettingsCheck.Problem> problems;

    public InvalidSettings(String task, List<TaskSettingsCheck.Problem> problems) {
        super("task '" + task + "' not started: " + problems.stream().map(p -> "key '" + task + "." + p.setting()
                + "': " + p.message()).collect(Collectors.joining("; ")));
        this.problems = List.copyOf(problems);
    }

    /** @return the problems, in the order found */
    public List<TaskSettingsCheck.Problem> problems() {
        return problems;
    }
}
