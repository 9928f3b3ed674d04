package sabot.onboard.remotefs.internal;

import java.util.List;
import java.util.Map;

import org.osgi.service.component.annotations.Component;

import sabot.onboard.task.TaskSettingsCheck;

/** What Metatype cannot say about the {@code remotefs} settings: the root must be an existing, readable directory. */
@Component(service = TaskSettingsCheck.class, property = TaskSettingsCheck.TASK + "=" + RemoteFsSettings.TASK)
public final class RemoteFsSettingsCheck implements TaskSettingsCheck {

    @Override
    public List<Problem> check(Map<String, Object> settings) {
        return RemoteFsSettings.problems(settings);
    }
}
