package sabot.workbench.splash.internal;

import java.io.File;
import java.io.IOException;
import java.nio.file.Files;
import java.util.concurrent.atomic.AtomicInteger;

import org.eclipse.core.runtime.IProgressMonitor;
import org.eclipse.swt.graphics.RGB;
import org.eclipse.swt.graphics.Rectangle;
import org.eclipse.swt.widgets.Display;
import org.eclipse.swt.widgets.Shell;
import org.eclipse.ui.splash.BasicSplashHandler;
import org.osgi.framework.Bundle;
import org.osgi.framework.BundleContext;
import org.osgi.framework.BundleEvent;
import org.osgi.framework.Constants;
import org.osgi.framework.FrameworkUtil;
import org.osgi.framework.SynchronousBundleListener;

/**
 * Splash screen of Sabot Workbench: the launcher's splash window with a progress bar and a message line that says
 * which plug-in (bundle) is starting, "Loading sabot.workbench.fleet" (thesis fig. 2.7). The bar advances one step per
 * bundle started, out of as many as the previous start started.
 *
 * <p>
 * Its own bundle listener rather than the workbench's startup listener: that one only runs when the preference
 * {@code org.eclipse.ui/SHOW_PROGRESS_ON_STARTUP} is set (a plugin_customization.ini the product does not have) and
 * counts service registrations, not plug-ins. The rectangles match the band that tools/splash/MakeSplash.java leaves
 * free at the bottom of splash.bmp (480 x 300 px).
 */
public final class ProgressSplashHandler extends BasicSplashHandler {

    /** Message line, in splash.bmp pixels: above the bar, in the dark band (which starts at y = 234). */
    static final Rectangle MESSAGE_RECT = new Rectangle(20, 244, 440, 18);
    /** Progress bar, in splash.bmp pixels. */
    static final Rectangle PROGRESS_RECT = new Rectangle(20, 272, 440, 12);
    /** Colour of the message text (the light blue-grey of the image's subtitle). */
    static final RGB FOREGROUND = new RGB(0xc8, 0xd8, 0xec);

    /** Most events dispatched after a bundle started (Workbench.spinEventQueueToUpdateSplash's bound). */
    static final int SPIN_EVENTS = 100;

    /** Shell data key the splash shell carries (value {@code Boolean.TRUE}): tells it apart from other shells. */
    public static final String SHELL_DATA_KEY = "sabot.workbench.splash";

    /** File in this bundle's data area: bundles the last start started while the splash was up. */
    static final String STARTED_FILE = "bundles-started";

    private BundleContext context;
    private SynchronousBundleListener listener;
    /** Bundles started since the splash came up (bundle events arrive on several threads). */
    private final AtomicInteger started = new AtomicInteger();

    @Override
    public void init(Shell splash) {
        super.init(splash);
        setMessageRect(MESSAGE_RECT);
        setProgressRect(PROGRESS_RECT);
        setForeground(FOREGROUND);
        getContent(); // creates the bar and the line now: BasicSplashHandler's contract
        splash.setData(SHELL_DATA_KEY, Boolean.TRUE);

        Bundle self = FrameworkUtil.getBundle(ProgressSplashHandler.class);
        context = self == null ? null : self.getBundleContext();
        if (context == null) {
            return; // not in OSGi (cannot happen in the product): a plain splash
        }
        IProgressMonitor monitor = getBundleProgressMonitor();
        monitor.beginTask("", expectedStarts(context));
        Display display = splash.getDisplay();
        listener = event -> {
            switch (event.getType()) {
                case BundleEvent.STARTING -> monitor.setTaskName("Loading " + event.getBundle().getSymbolicName());
                case BundleEvent.STARTED -> {
                    started.incrementAndGet();
                    monitor.worked(1);
                }
                default -> {
                    return;
                }
            }
            // the workbench starts most bundles on the UI thread (lazy activation while it builds the window), whose
            // event loop is not running yet: draw the change now and let pending events through, as the workbench's
            // own startup listener does (at most SPIN_EVENTS, so startup cannot stall here)
            if (display.getThread() == Thread.currentThread() && !display.isDisposed()) {
                display.update();
                if (event.getType() == BundleEvent.STARTED) {
                    for (int i = 0; i < SPIN_EVENTS && display.readAndDispatch(); i++) {
                        // dispatching
                    }
                }
            }
        };
        context.addBundleListener(listener);
    }

    /**
     * How many bundles this start will start while the splash is up: as many as the last start did (remembered in
     * this bundle's data area), else an estimate from the bundles that can still start (not active, not fragments,
     * with an activator or lazy activation); most lazy bundles of the platform are never started, so the first start's
     * bar fills only part of the way.
     */
    private static int expectedStarts(BundleContext context) {
        File memory = context.getDataFile(STARTED_FILE);
        if (memory != null && memory.isFile()) {
            try {
                int n = Integer.parseInt(Files.readString(memory.toPath()).trim());
                if (n > 0) {
                    return n;
                }
            } catch (IOException | NumberFormatException unreadable) {
                // estimate instead
            }
        }
        int estimate = 0;
        for (Bundle b : context.getBundles()) {
            var headers = b.getHeaders("");
            boolean startable = headers.get(Constants.BUNDLE_ACTIVATOR) != null
                    || headers.get(Constants.BUNDLE_ACTIVATIONPOLICY) != null
                    || headers.get("Service-Component") != null;
            if (headers.get(Constants.FRAGMENT_HOST) == null && b.getState() != Bundle.ACTIVE && startable) {
                estimate++;
            }
        }
        return Math.max(1, estimate);
    }

    @Override
    public void dispose() {
        if (context != null && listener != null) {
            try {
                context.removeBundleListener(listener);
                File memory = context.getDataFile(STARTED_FILE);
                if (memory != null && started.get() > 0) {
                    Files.writeString(memory.toPath(), Integer.toString(started.get()));
                }
            } catch (IllegalStateException | IOException stopping) {
                // the bundle is being stopped, or its data area is not writable: the next bar is an estimate
            }
        }
        super.dispose();
    }
}
