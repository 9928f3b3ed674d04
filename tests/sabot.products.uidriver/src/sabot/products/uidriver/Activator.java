package sabot.products.uidriver;

import org.osgi.framework.BundleActivator;
import org.osgi.framework.BundleContext;

/**
 * Starts the {@link UiDriver} on its own thread when the system property {@value UiDriver#STEPS} is set. Test only:
 * tests/sabot.products.tests puts this bundle into a copy of the materialized workbench through {@code osgi.bundles}
 * (it is in no feature and on no update site).
 */
public final class Activator implements BundleActivator {

    private Thread thread;

    @Override
    public void start(BundleContext context) {
        String steps = System.getProperty(UiDriver.STEPS);
        if (steps == null || steps.isBlank()) {
            return;
        }
        thread = new Thread(new UiDriver(context, steps), "sabot-uidriver");
        thread.setDaemon(true);
        thread.start();
    }

    @Override
    public void stop(BundleContext context) {
        if (thread != null) {
            thread.interrupt();
        }
    }
}
