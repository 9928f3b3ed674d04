package sabot.workbench.internal;

import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentSkipListMap;
import java.util.concurrent.atomic.AtomicBoolean;

import org.eclipse.swt.widgets.Display;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;
import org.osgi.framework.ServiceReference;
import org.osgi.util.tracker.ServiceTracker;
import org.osgi.util.tracker.ServiceTrackerCustomizer;

import sabot.workbench.fleet.ConnectionStatus;
import sabot.workbench.fleet.FleetListener;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotState;

/**
 * A view's tie to the {@link FleetState} service (thesis rule 1: the core observes the ControlML plug-in). It follows
 * the service as it comes and goes (the plug-in is optional), keeps the latest state of each robot, and runs the
 * view's refresh on the UI thread at most once per burst of changes: a hundred robots at 10 Hz are a thousand events a
 * second, the screen needs one repaint per frame.
 */
public final class FleetBinding implements FleetListener {

    private final Display display;
    private final Runnable refresh;
    private final ServiceTracker<FleetState, FleetState> tracker;
    private final Map<String, RobotState> robots = new ConcurrentSkipListMap<>();
    private final AtomicBoolean scheduled = new AtomicBoolean();
    private volatile ConnectionStatus status;
    private volatile boolean disposed;

    /**
     * @param display the UI thread's display
     * @param refresh runs on the UI thread after changes
     */
    public FleetBinding(Display display, Runnable refresh) {
        this.display = display;
        this.refresh = refresh;
        BundleContext context = FrameworkUtil.getBundle(FleetBinding.class).getBundleContext();
        tracker = new ServiceTracker<>(context, FleetState.class, new ServiceTrackerCustomizer<>() {
            @Override
            public FleetState addingService(ServiceReference<FleetState> reference) {
                FleetState fleet = context.getService(reference);
                fleet.addListener(FleetBinding.this);
                return fleet;
            }

            @Override
            public void modifiedService(ServiceReference<FleetState> reference, FleetState service) {
                // nothing: the service has no properties the views use
            }

            @Override
            public void removedService(ServiceReference<FleetState> reference, FleetState fleet) {
                fleet.removeListener(FleetBinding.this);
                context.ungetService(reference);
                robots.clear();
                status = null;
                schedule();
            }
        });
        tracker.open();
    }

    /** @return the fleet service, or null while no ControlML plug-in provides one */
    public FleetState fleet() {
        return tracker.getService();
    }

    /** @return the robots as last reported, sorted by JID */
    public List<RobotState> robots() {
        return List.copyOf(robots.values());
    }

    /** @return a robot as last reported, or null */
    public RobotState robot(String jid) {
        return jid == null ? null : robots.get(jid);
    }

    /** @return the connection as last reported, or null without a fleet service */
    public ConnectionStatus status() {
        return status;
    }

    @Override
    public void robotChanged(RobotState robot) {
        robots.put(robot.jid(), robot);
        schedule();
    }

    @Override
    public void robotRemoved(String jid) {
        robots.remove(jid);
        schedule();
    }

    @Override
    public void connectionChanged(ConnectionStatus s) {
        status = s;
        schedule();
    }

    private void schedule() {
        if (!disposed && scheduled.compareAndSet(false, true) && !display.isDisposed()) {
            display.asyncExec(() -> {
                scheduled.set(false);
                if (!disposed) {
                    refresh.run();
                }
            });
        }
    }

    /** Stops observing (the view is closing). */
    public void dispose() {
        disposed = true;
        tracker.close();
    }
}
