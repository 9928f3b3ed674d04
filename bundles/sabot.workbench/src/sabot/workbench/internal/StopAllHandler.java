package sabot.workbench.internal;

import org.eclipse.core.commands.AbstractHandler;
import org.eclipse.core.commands.ExecutionEvent;
import org.eclipse.core.commands.ExecutionException;
import org.eclipse.ui.IWorkbenchPage;
import org.eclipse.ui.IWorkbenchWindow;
import org.eclipse.ui.handlers.HandlerUtil;
import org.osgi.framework.FrameworkUtil;
import org.osgi.util.tracker.ServiceTracker;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.workbench.fleet.FleetState;
import sabot.workbench.views.WorkspaceView;

/**
 * Robot › Stop All Robots (toolbar, and Ctrl+Shift+H while the Workspace or Fleet view is active): every online robot
 * of the fleet is stopped, in a job; the outcome (with each robot's refusal text) appears in the status line and on
 * the map.
 */
public final class StopAllHandler extends AbstractHandler {

    /** The command (plugin.xml). */
    public static final String COMMAND_ID = "sabot.workbench.commands.stopAll";

    private static final Logger LOG = LoggerFactory.getLogger("sabot.workbench");

    @Override
    public Object execute(ExecutionEvent event) throws ExecutionException {
        IWorkbenchWindow window = HandlerUtil.getActiveWorkbenchWindowChecked(event);
        IWorkbenchPage page = window.getActivePage();
        WorkspaceView workspace = page == null ? null : (WorkspaceView) page.findView(WorkspaceView.ID);
        LOG.info("{} (command)", FleetJobs.STOP_ALL);
        FleetJobs.stopAll(window.getShell().getDisplay(), fleet(), (text, failed) -> {
            if (workspace != null && workspace.canvas() != null && !workspace.canvas().isDisposed()) {
                workspace.show(text, failed);
            }
        });
        return null;
    }

    /** The fleet service while the handler lives (the plug-in is optional: it comes and goes). */
    private final ServiceTracker<FleetState, FleetState> fleet = new ServiceTracker<>(FrameworkUtil.getBundle(
            StopAllHandler.class).getBundleContext(), FleetState.class, null);

    public StopAllHandler() {
        fleet.open();
    }

    /** @return the fleet service now, or null without the ControlML plug-in (the job then says so) */
    private FleetState fleet() {
        return fleet.getService();
    }

    @Override
    public void dispose() {
        fleet.close();
        super.dispose();
    }
}
