package sabot.workbench.views;

import java.lang.management.ManagementFactory;
import java.lang.management.ThreadMXBean;

/**
 * The Workspace view's paints as the tests measure them: how many, each one's wall time and UI-thread CPU time (the
 * last {@value #SAMPLES}), and when the last one ended. Observes one view from {@link #of} to {@link #close}.
 */
public final class FrameStatistics implements WorkspacePaintObserver, AutoCloseable {

    /** Paints kept. */
    private static final int SAMPLES = 4096;

    private final WorkspaceView view;
    private final ThreadMXBean threads = ManagementFactory.getThreadMXBean();
    private final long[] wallNanos = new long[SAMPLES];
    private final long[] cpuNanos = new long[SAMPLES];
    private long cpuAtStart;
    private volatile int count;
    private volatile long lastEndNanos;

    private FrameStatistics(WorkspaceView view) {
        this.view = view;
    }

    /** @return statistics of the paints of {@code view} from its next paint on (UI thread) */
    public static FrameStatistics of(WorkspaceView view) {
        FrameStatistics s = new FrameStatistics(view);
        view.addPaintObserver(s);
        return s;
    }

    @Override
    public void paintStarting() {
        cpuAtStart = threads.getCurrentThreadCpuTime();
    }

    @Override
    public void painted(Paint paint) {
        int i = count % SAMPLES;
        wallNanos[i] = paint.endNanos() - paint.startNanos();
        cpuNanos[i] = threads.getCurrentThreadCpuTime() - cpuAtStart;
        lastEndNanos = paint.endNanos();
        count++;
    }

    /** @return the paints so far */
    public int count() {
        return count;
    }

    /** @return {@link System#nanoTime()} at the end of the last paint, 0 before the first */
    public long lastEndNanos() {
        return lastEndNanos;
    }

    /** @return the paints' durations so far, ns, oldest first */
    public long[] wallNanos() {
        return last(wallNanos);
    }

    /** @return the paints' UI-thread CPU times so far, ns, as {@link #wallNanos} */
    public long[] cpuNanos() {
        return last(cpuNanos);
    }

    private long[] last(long[] ring) {
        int frames = count;
        int n = Math.min(frames, SAMPLES);
        long[] out = new long[n];
        for (int i = 0; i < n; i++) {
            out[i] = ring[(frames - n + i) % SAMPLES];
        }
        return out;
    }

    @Override
    public void close() {
        view.removePaintObserver(this);
    }
}
