package sabot.onboard.controlml.internal.peers;

import java.util.List;
import java.util.Map;

import org.osgi.service.component.annotations.Component;

import sabot.onboard.task.TaskSettingsCheck;

/**
 * What Metatype cannot say about the {@code peers} settings: the robots' group must be named, without control
 * characters (and the rate is checked again, as for any Config Admin client).
 */
@Component(service = TaskSettingsCheck.class, property = TaskSettingsCheck.TASK + "=" + PeersSettings.TASK)
public final class PeersSettingsCheck implements TaskSettingsCheck {

    @Override
    public List<Problem> check(Map<String, Object> settings) {
        return PeersSettings.problems(settings);
    }
}
