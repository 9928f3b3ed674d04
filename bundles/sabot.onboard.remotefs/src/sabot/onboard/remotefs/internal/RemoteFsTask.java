package sabot.onboard.remotefs.internal;

import java.io.IOException;
import java.util.Map;

import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;
import org.osgi.service.component.annotations.Deactivate;
import org.osgi.service.component.annotations.Reference;
import org.osgi.service.metatype.annotations.Designate;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.onboard.session.RobotSession;
import sabot.onboard.task.OnboardTask;

/**
 * The {@code remotefs} task: serves {@code cm.fs.*} on the robot's session ({@link RemoteFileService}) from
 * activation to deactivation. The handlers live on the session's ControlML manager, so they keep serving across
 * reconnections. Settings: {@link RemoteFsSettings.Config}, checked by {@link RemoteFsSettingsCheck}.
 */
@Designate(ocd = RemoteFsSettings.Config.class, factory = false)
@Component(name = "sabot.task.remotefs", configurationPolicy = ConfigurationPolicy.REQUIRE, immediate = true,
        service = OnboardTask.class)
public final class RemoteFsTask implements OnboardTask {

    private static final Logger LOG = LoggerFactory.getLogger(RemoteFsTask.class);

    private final RobotSession session;
    private final RemoteFileService service;

    @Activate
    public RemoteFsTask(@Reference RobotSession session, Map<String, Object> properties) throws IOException {
        RemoteFsSettings settings = RemoteFsSettings.of(properties);
        this.session = session;
        this.service = new RemoteFileService(settings.root(), settings.limits());
        service.register(session.controlMl());
        LOG.info("remote FS task started: {} ({}), chunks of {} bytes, files up to {} bytes", service.root(),
                settings.limits().readOnly() ? "read-only" : "writable", settings.limits().maxChunk(), settings
                        .limits().maxFileSize());
    }

    @Deactivate
    void deactivate() {
        service.unregister(session.controlMl());
        LOG.info("remote FS task stopped ({} transfer(s) left unfinished)", service.transfersInProgress());
    }

    @Override
    public String name() {
        return RemoteFsSettings.TASK;
    }

    @Override
    public String status() {
        return "serving " + service.root() + (service.limits().readOnly() ? " read-only" : "") + ", "
                + service.transfersInProgress() + " transfer(s) in progress";
    }
}
