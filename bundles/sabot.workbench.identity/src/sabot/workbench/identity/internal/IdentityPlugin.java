package sabot.workbench.identity.internal;

import org.osgi.framework.BundleContext;
import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.slf4j.LoggerFactory;

/** Says in the log that the installed plug-in started, naming its view (the installation tests wait for it). */
@Component(immediate = true, service = IdentityPlugin.class)
public final class IdentityPlugin {

    @Activate
    void activate(BundleContext context) {
        LoggerFactory.getLogger("sabot.workbench.identity").info("Sabot identity plug-in {} active (view {})", context
                .getBundle().getVersion(), IdentityView.ID);
    }
}
