package sabot.workbench.fleet;

import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Set;
import java.util.concurrent.ConcurrentSkipListMap;
import java.util.concurrent.Executor;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicLong;

import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;
import org.osgi.framework.ServiceReference;
import org.osgi.util.tracker.ServiceTracker;
import org.osgi.util.tracker.ServiceTrackerCustomizer;

/**
 * A view's tie to the {@link FleetState} service (thesis rule 1: the core and the plug-ins observe the ControlML
 * plug-in). It follows the service as it comes and goes (the plug-in is optional), keeps the latest state of each
 * robot, and runs the view's refresh on the UI thread at most once per burst of changes: a hundred robots at 10 Hz are
 * a thousand events a second, the screen needs one repaint per frame.
 * <p>
 * No toolkit type: the UI thread is given as an {@link Executor} (with SWT: {@code display::asyncExec}, guarded by
 * {@code display.isDisposed()}). The service is tracked with this API bundle's context (the bundle activates lazily
 * on the first use of this class).
 */
public final class FleetBinding implements FleetListener {

    private final Executor uiThread;
    private final Runnable refresh;
    private final ServiceTracker<FleetState, FleetState> tracker;
    private final Map<String, RobotState> robots = new ConcurrentSkipListMap<>();
    private final AtomicBoolean scheduled = new AtomicBoolean();
    private volatile ConnectionStatus status;
    private volatile List<String> accessRequests = List.of();
    private volatile List<QueuedCommand> queued = List.of();
    private volatile boolean disposed;
    /** This view's name towards {@link FleetState#watch}: unique in the workbench. */
    private final String viewer = "view-" + VIEWERS.incrementAndGet();
    private static final AtomicLong VIEWERS = new AtomicLong();
    private Map<String, Double> watched = Map.of(); // guarded by this

    /**
     * Starts observing at once (the present state arrives with the first refresh).
     *
     * @param uiThread runs a task on the UI thread later (never in the caller's stack); it may refuse with
     *                 {@link RejectedExecutionException} or any runtime exception once the UI is gone
     * @param refresh  runs on the UI thread after changes
     */
    public FleetBinding(Executor uiThread, Runnable refresh) {
        this.uiThread = Objects.requireNonNull(uiThread, "uiThread");
        this.refresh = Objects.requireNonNull(refresh, "refresh");
        BundleContext context = FrameworkUtil.getBundle(FleetBinding.class).getBundleContext();
        if (context == null) {
            throw new IllegalStateException("bundle " + FrameworkUtil.getBundle(FleetBinding.class)
                    .getSymbolicName() + " is not active (it needs Bundle-ActivationPolicy: lazy and a started state)");
        }
        tracker = new ServiceTracker<>(context, FleetState.class, new ServiceTrackerCustomizer<>() {
            @Override
            public FleetState addingService(ServiceReference<FleetState> reference) {
                FleetState fleet = context.getService(reference);
                fleet.addListener(FleetBinding.this);
                synchronized (FleetBinding.this) {
                    if (!watched.isEmpty()) {
                        fleet.watch(viewer, watched); // what this view said before the service came
                    }
                }
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
                accessRequests = List.of();
                queued = List.of();
                schedule();
            }
        });
        tracker.open();
    }

    /** @return the fleet service, or null while no ControlML plug-in provides one */
    public FleetState fleet() {
        return tracker.getService();
    }

    /** @return the robots as last reported, sorted by bare JID; empty without a fleet */
    public List<RobotState> robots() {
        return List.copyOf(robots.values());
    }

    /** @return a robot as last reported, or null (also for a null JID) */
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

    /** @return the robots asking for access as last reported ({@link FleetState#accessRequests()}) */
    public List<String> accessRequests() {
        return accessRequests;
    }

    @Override
    public void accessRequestsChanged(List<String> jids) {
        accessRequests = List.copyOf(jids);
        schedule();
    }

    /** @return the commands waiting for offline robots as last reported ({@link FleetState#queuedCommands()}) */
    public List<QueuedCommand> queuedCommands() {
        return queued;
    }

    @Override
    public void queuedCommandsChanged(List<QueuedCommand> now) {
        queued = List.copyOf(now);
        schedule();
    }

    private void schedule() {
        if (!disposed && scheduled.compareAndSet(false, true)) {
            try {
                uiThread.execute(() -> {
                    scheduled.set(false);
                    if (!disposed) {
                        refresh.run();
                    }
                });
            } catch (RuntimeException uiGone) {
                // the display is being disposed: nothing is left to refresh
                scheduled.set(false);
            }
        }
    }

    /**
     * Tells the fleet which robots this view shows and how often it needs their telemetry ({@link FleetState#watch});
     * said again to a fleet service that comes later, and ended by {@link #dispose}. A call that changes nothing
     * costs nothing: a view may call it at every frame.
     *
     * @param rates Hz by robot (bare JID), e.g. {@link FleetState#SHOWN_HZ} or {@link FleetState#LISTED_HZ}; empty:
     *              none
     */
    public synchronized void watch(Map<String, Double> rates) {
        if (disposed || rates.equals(watched)) {
            return;
        }
        watched = Map.copyOf(rates);
        FleetState fleet = fleet();
        if (fleet != null) {
            fleet.watch(viewer, watched);
        }
    }

    /** {@link #watch(Map)} of these robots, all at {@code hz}. */
    public void watch(Set<String> robots, double hz) {
        Map<String, Double> rates = new HashMap<>();
        robots.forEach(r -> rates.put(r, hz));
        watch(rates);
    }

    /** Stops observing (the view is closing); no refresh runs afterwards. */
    public void dispose() {
        synchronized (this) {
            disposed = true;
            FleetState fleet = fleet();
            if (fleet != null && !watched.isEmpty()) {
                fleet.watch(viewer, Map.of());
            }
            watched = Map.of();
        }
        tracker.close();
    }
}
