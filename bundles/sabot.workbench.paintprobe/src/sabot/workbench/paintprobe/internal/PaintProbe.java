package sabot.workbench.paintprobe.internal;

import java.nio.file.Paths;

import org.osgi.framework.BundleContext;
import org.osgi.framework.ServiceRegistration;
import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.Deactivate;

import sabot.workbench.views.WorkspacePaintObserver;

/**
 * Measurement probe of {@code ./sabot bench workbench}, registered as a {@link WorkspacePaintObserver} only when the
 * system property {@value #PROPERTY} names a file (the bench sets it; otherwise the workbench has no probe at all):
 * records each Workspace paint's duration and, for every robot pose a paint shows for the first time, the
 * latency from the pose's time stamp (the robot's clock: on one host the same clock) to the end of that paint; also,
 * as a breakdown, the latency from the time stamp to the moment the fleet service notified its listeners.
 * <p>
 * Lines appended to the file, written by a daemon thread every 250 ms (the UI thread only fills a buffer):
 * <ul>
 * <li>{@code f,<end µs since the epoch>,<paint duration ns>,<robots drawn>,<UI thread CPU time of the paint ns>,<of
 * the duration, the frame's copy to the window ns>,<of the duration, the UI thread runnable but waiting for a CPU ns,
 * -1 where Linux's schedstat is missing>}</li>
 * <li>{@code l,<end µs since the epoch>,<time stamp to paint end ns>,<robot jid>}</li>
 * <li>{@code n,<µs since the epoch>,<time stamp to notification ns>,<robot jid>}</li>
 * </ul>
 */
@Component(immediate = true, service = {})
public final class PaintProbe {

    /** System property naming the file the probe appends to; without it the probe does nothing. */
    public static final String PROPERTY = "sabot.workbench.paintProbe";

    private PaintRecorder recorder;
    private ServiceRegistration<WorkspacePaintObserver> registration;

    @Activate
    void activate(BundleContext context) {
        String f = context.getProperty(PROPERTY);
        if (f != null && !f.isBlank()) {
            recorder = new PaintRecorder(Paths.get(f));
            registration = context.registerService(WorkspacePaintObserver.class, recorder, null);
        }
    }

    @Deactivate
    void deactivate() {
        if (registration != null) {
            registration.unregister();
            recorder.stop();
        }
    }
}
