package sabot.onboard.portal.internal;

import java.util.List;
import java.util.Map;

import org.osgi.service.component.annotations.Component;

import sabot.onboard.task.TaskSettingsCheck;

/** What Metatype cannot say about the {@code portal} settings: an IP address to bind, readable PEM files for HTTPS. */
@Component(service = TaskSettingsCheck.class, property = TaskSettingsCheck.TASK + "=" + PortalSettings.TASK)
public final class PortalSettingsCheck implements TaskSettingsCheck {

    @Override
    public List<Problem> check(Map<String, Object> settings) {
        return PortalSettings.problems(settings);
    }
}
