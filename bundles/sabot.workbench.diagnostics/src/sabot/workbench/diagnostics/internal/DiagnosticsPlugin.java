package sabot.workbench.diagnostics.internal;

import org.osgi.framework.BundleContext;
import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Announces the plug-in once it is installed and started: one log line with the plug-in's version and a runtime
 * summary. Installation tests look for it after the p2 director has installed the feature.
 */
@Component(immediate = true, service = DiagnosticsPlugin.class)
public final class DiagnosticsPlugin {

    private static final Logger LOG = LoggerFactory.getLogger("sabot.workbench.diagnostics");

    @Activate
    void activate(BundleContext context) {
        LOG.info("Sabot diagnostics plug-in {} active: {}", context.getBundle().getVersion(), RuntimeReport.summary(
                context));
    }
}
