package sabot.onboard.controlml.internal.session;

import java.util.List;
import java.util.Map;

import org.osgi.service.component.annotations.Component;

import sabot.onboard.task.TaskSettingsCheck;

/**
 * What Metatype cannot say about the {@code controlml} settings: the JIDs' syntax, the password file (exists, is a
 * regular file, readable, private to its owner, not empty) and reconnectMin &le; reconnectMax.
 */
@Component(service = TaskSettingsCheck.class, property = TaskSettingsCheck.TASK + "=" + ControlMlSettings.TASK)
public final class ControlMlSettingsCheck implements TaskSettingsCheck {

    @Override
    public List<Problem> check(Map<String, Object> settings) {
        return ControlMlSettings.problems(settings);
    }
}
