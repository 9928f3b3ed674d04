package sabot.workbench.views;

import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import java.util.concurrent.CopyOnWriteArrayList;

import org.osgi.framework.Bundle;
import org.osgi.framework.FrameworkUtil;
import org.osgi.util.tracker.ServiceTracker;

/**
 * The {@link WorkspacePaintObserver}s of one view: those added to it and those registered as OSGi services (tracked
 * from {@link #open} to {@link #close}).
 */
final class PaintObservers {

    private final List<WorkspacePaintObserver> added = new CopyOnWriteArrayList<>();
    private ServiceTracker<WorkspacePaintObserver, WorkspacePaintObserver> services;

    /** Tracks the observer services (nothing outside OSGi). */
    void open() {
        Bundle bundle = FrameworkUtil.getBundle(PaintObservers.class);
        if (bundle != null && bundle.getBundleContext() != null) {
            services = new ServiceTracker<>(bundle.getBundleContext(), WorkspacePaintObserver.class, null);
            services.open();
        }
    }

    void close() {
        if (services != null) {
            services.close();
        }
    }

    void add(WorkspacePaintObserver observer) {
        added.add(Objects.requireNonNull(observer));
    }

    void remove(WorkspacePaintObserver observer) {
        added.remove(observer);
    }

    /** @return the observers of the paint that begins: those added and the services' */
    List<WorkspacePaintObserver> now() {
        Object[] registered = services == null ? null : services.getServices();
        if (registered == null) {
            return added;
        }
        List<WorkspacePaintObserver> all = new ArrayList<>(added);
        for (Object s : registered) {
            all.add((WorkspacePaintObserver) s);
        }
        return all;
    }
}
