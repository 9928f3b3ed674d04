package sabot.workbench.statistics.internal;

import org.osgi.framework.BundleContext;
import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.slf4j.LoggerFactory;

/** The started plug-in's log line with its version and view, which the installation tests look for. */
@Component(immediate = true, service = StatisticsPlugin.class)
public final class StatisticsPlugin {

    @Activate
    void activate(BundleContext context) {
        LoggerFactory.getLogger("sabot.workbench.statistics").info("Sabot statistics plug-in {} active (view {})",
                context.getBundle().getVersion(), TrafficView.ID);
    }
}
