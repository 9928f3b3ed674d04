package sabot.workbench.remotefs.internal;

import org.osgi.framework.BundleContext;
import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.slf4j.LoggerFactory;

/** Announces the installed and started plug-in in the log (the installation tests look for the line). */
@Component(immediate = true, service = RemoteFilesPlugin.class)
public final class RemoteFilesPlugin {

    @Activate
    void activate(BundleContext context) {
        LoggerFactory.getLogger("sabot.workbench.remotefs").info("Sabot remote files plug-in {} active (view {})",
                context.getBundle().getVersion(), RemoteFilesView.ID);
    }
}
