package sabot.workbench.internal;

import org.eclipse.equinox.app.IApplication;
import org.eclipse.equinox.app.IApplicationContext;
import org.eclipse.swt.widgets.Display;
import org.eclipse.ui.IWorkbench;
import org.eclipse.ui.PlatformUI;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;
import org.slf4j.bridge.SLF4JBridgeHandler;

/** The Sabot Workbench RCP application (3.x workbench API on the e4 compatibility layer). */
public final class WorkbenchApplication implements IApplication {

    private static final Logger LOG = LoggerFactory.getLogger("sabot.workbench");

    @Override
    public Object start(IApplicationContext context) {
        // Smack logs through java.util.logging: into SLF4J, so that etc/logback.xml governs its lines too
        SLF4JBridgeHandler.removeHandlersForRootLogger();
        SLF4JBridgeHandler.install();
        String[] args = (String[]) context.getArguments().getOrDefault(IApplicationContext.APPLICATION_ARGS,
                new String[0]);
        LaunchOptions options = LaunchOptions.parse(args);
        Display display = PlatformUI.createDisplay();
        installSignalHandlers(display);
        try {
            LOG.info("Sabot Workbench starting");
            int code = PlatformUI.createAndRunWorkbench(display, new SabotWorkbenchAdvisor(options));
            LOG.info("Sabot Workbench stopped");
            return code == PlatformUI.RETURN_RESTART ? IApplication.EXIT_RESTART : IApplication.EXIT_OK;
        } finally {
            display.dispose();
        }
    }

    @Override
    public void stop() {
        if (!PlatformUI.isWorkbenchRunning()) {
            return;
        }
        IWorkbench workbench = PlatformUI.getWorkbench();
        Display display = workbench.getDisplay();
        display.syncExec(() -> {
            if (!display.isDisposed()) {
                workbench.close();
            }
        });
    }

    /**
     * SIGTERM and SIGINT close the workbench the way File > Exit does (state saved, exit status 0) instead of the
     * JVM's abrupt exit with 143/130.
     */
    @SuppressWarnings("restriction")
    private static void installSignalHandlers(Display display) {
        for (String name : new String[] { "TERM", "INT" }) {
            try {
                sun.misc.Signal.handle(new sun.misc.Signal(name), signal -> {
                    LOG.info("received SIG{}, closing the workbench", signal.getName());
                    if (!display.isDisposed()) {
                        display.asyncExec(() -> {
                            if (PlatformUI.isWorkbenchRunning()) {
                                PlatformUI.getWorkbench().close();
                            }
                        });
                    }
                });
            } catch (IllegalArgumentException unsupported) {
                LOG.warn("cannot handle SIG{}: {}", name, unsupported.getMessage());
            }
        }
    }
}
