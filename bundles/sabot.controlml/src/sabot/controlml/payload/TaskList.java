package sabot.controlml.payload;

import java.util.List;

/** {@code cm.tasks}: the loaded tasks. @param tasks never null */
public record TaskList(List<TaskInfo> tasks) {
    public TaskList {
        tasks = List.copyOf(tasks);
    }
}
