package sabot.controlml.payload;

import java.util.ArrayList;
import java.util.List;
import java.util.Set;

import sabot.controlml.swe.SweComponent;

/** {@code cm.tasks}: the loaded tasks. @param tasks never null */
public record TaskList(List<TaskInfo> tasks) {
    public TaskList {
        tasks = List.copyOf(tasks);
    }

    private static final Set<String> TASK_STATES = Set.of("installed", "resolved", "active", "starting", "stopping");

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<TaskList> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(TaskList t) {
            RecordBuilder b = new RecordBuilder().count("count", t.tasks().size());
            int i = 0;
            for (TaskInfo task : t.tasks()) {
                b.add("task" + i++, new RecordBuilder().text("name", task.name()).text("bundle", task.bundle())
                        .text("version", task.version())
                        .category("state", task.state()).build());
            }
            return b.build();
        }

        @Override
        public TaskList decode(SweComponent payload) throws PayloadException {
            String[] names = RecordReader.indexedFields(payload, "task", 256);
            RecordReader r = RecordReader.of(payload, names);
            List<TaskInfo> tasks = new ArrayList<>();
            for (int i = 1; i < names.length; i++) {
                RecordReader t = r.record(names[i], "name", "bundle", "version", "state");
                tasks.add(new TaskInfo(t.text("name", 128), t.text("bundle", 255), t.text("version", 64),
                        t.category("state", TASK_STATES)));
            }
            return new TaskList(tasks);
        }
    };
}
