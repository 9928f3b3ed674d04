package sabot.workbench.paintprobe.internal;

import java.io.BufferedWriter;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.nio.file.StandardOpenOption;
import java.time.Instant;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.TimeUnit;

import sabot.workbench.fleet.FleetListener;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.views.WorkspacePaintObserver;

/**
 * The paint probe's recorder ({@link PaintProbe}): the paints' lines on the UI thread into a buffer, the fleet
 * service's notifications from its thread, and the file from a daemon thread every 250 ms.
 */
final class PaintRecorder implements WorkspacePaintObserver, FleetListener {

    /** Linux's scheduler statistics of the calling thread: CPU time, time runnable but waiting for a CPU (ns), ... */
    private static final Path SCHEDSTAT = Paths.get("/proc/thread-self/schedstat");

    private final Path file;
    private final Thread writer;
    private final StringBuilder pending = new StringBuilder();
    /** Pose time stamps already shown per robot (UI thread only). */
    private final Map<String, Instant> shown = new HashMap<>();
    /** Pose time stamps already notified per robot (notification thread). */
    private final Map<String, Instant> notified = new ConcurrentHashMap<>();
    private FleetState observed;
    private final java.lang.management.ThreadMXBean threads = java.lang.management.ManagementFactory.getThreadMXBean();
    private long cpuAtStart;
    private long queuedAtStart;

    PaintRecorder(Path file) {
        this.file = file;
        writer = new Thread(this::writeLoop, "sabot-paint-probe");
        writer.setDaemon(true);
        writer.start();
    }

    void stop() {
        writer.interrupt();
        if (observed != null) {
            observed.removeListener(this);
        }
    }

    /** UI thread, at the start of a paint: the paint's CPU time (apart from the wall time other processes stretch). */
    @Override
    public void paintStarting() {
        cpuAtStart = threads.getCurrentThreadCpuTime();
        queuedAtStart = runQueueWait();
    }

    /** UI thread, at the end of a paint. */
    @Override
    public void painted(Paint paint) {
        long duration = System.nanoTime() - paint.startNanos();
        List<RobotState> robots = paint.robots();
        FleetState fleet = paint.fleet();
        long copyNanos = paint.copyNanos();
        long cpu = threads.getCurrentThreadCpuTime() - cpuAtStart;
        long queued = queuedAtStart < 0 ? -1 : runQueueWait() - queuedAtStart;
        Instant end = Instant.now();
        long endMicros = micros(end);
        if (fleet != null && fleet != observed) {
            observed = fleet;
            fleet.addListener(this);
        }
        StringBuilder lines = new StringBuilder(64 + 48 * robots.size());
        lines.append("f,").append(endMicros).append(',').append(duration).append(',').append(robots.size()).append(
                ',').append(cpu).append(',').append(copyNanos).append(',').append(queued).append('\n');
        for (RobotState r : robots) {
            if (r.pose() == null) {
                continue;
            }
            Instant t = r.pose().time();
            Instant before = shown.put(r.jid(), t);
            if (before == null || t.isAfter(before)) {
                lines.append("l,").append(endMicros).append(',').append(nanosBetween(t, end)).append(',').append(r
                        .jid()).append('\n');
            }
        }
        synchronized (pending) {
            pending.append(lines);
        }
    }

    @Override
    public void robotChanged(RobotState r) {
        if (r.pose() == null) {
            return;
        }
        Instant now = Instant.now();
        Instant t = r.pose().time();
        Instant before = notified.put(r.jid(), t);
        if (before == null || t.isAfter(before)) {
            String line = "n," + micros(now) + "," + nanosBetween(t, now) + "," + r.jid() + "\n";
            synchronized (pending) {
                pending.append(line);
            }
        }
    }

    /**
     * @return the calling thread's time runnable but not running so far (ns, the second field of Linux's
     *         {@code /proc/thread-self/schedstat}), or -1 where the file is missing
     */
    private static long runQueueWait() {
        try {
            return Long.parseLong(Files.readString(SCHEDSTAT).split(" ")[1]);
        } catch (IOException | RuntimeException e) {
            return -1;
        }
    }

    private void writeLoop() {
        try (BufferedWriter out = Files.newBufferedWriter(file, StandardCharsets.US_ASCII, StandardOpenOption.CREATE,
                StandardOpenOption.APPEND)) {
            while (true) {
                String chunk;
                synchronized (pending) {
                    // a timed wait, not a sleep: nothing signals it; the period bounds how late the file is
                    pending.wait(TimeUnit.MILLISECONDS.toMillis(250));
                    chunk = pending.toString();
                    pending.setLength(0);
                }
                if (!chunk.isEmpty()) {
                    out.write(chunk);
                    out.flush();
                }
            }
        } catch (IOException e) {
            org.slf4j.LoggerFactory.getLogger("sabot.workbench").warn("paint probe: {}", e.toString());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    private static long micros(Instant t) {
        return t.getEpochSecond() * 1_000_000L + t.getNano() / 1000;
    }

    private static long nanosBetween(Instant a, Instant b) {
        return (b.getEpochSecond() - a.getEpochSecond()) * 1_000_000_000L + (b.getNano() - a.getNano());
    }
}
