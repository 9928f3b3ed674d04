package sabot.workbench.internal;

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

/**
 * Measurement hook of {@code ./sabot bench workbench} (off unless the system property {@value #PROPERTY} names a
 * file): records each Workspace paint's duration and, for every robot pose a paint shows for the first time, the
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
public final class PaintProbe implements FleetListener {

    /** System property naming the file the probe appends to; without it the probe does nothing. */
    public static final String PROPERTY = "sabot.workbench.paintProbe";

    private static final PaintProbe OFF = new PaintProbe(null);

    private final Path file;
    private final StringBuilder pending = new StringBuilder();
    /** Pose time stamps already shown per robot (UI thread only). */
    private final Map<String, Instant> shown = new HashMap<>();
    /** Pose time stamps already notified per robot (notification thread). */
    private final Map<String, Instant> notified = new ConcurrentHashMap<>();
    private FleetState observed;
    private final java.lang.management.ThreadMXBean threads = java.lang.management.ManagementFactory.getThreadMXBean();
    private long cpuAtStart;
    private long queuedAtStart;
    /** Linux's scheduler statistics of the calling thread: CPU time, time runnable but waiting for a CPU (ns), ... */
    private static final Path SCHEDSTAT = Paths.get("/proc/thread-self/schedstat");

    private PaintProbe(Path file) {
        this.file = file;
        if (file != null) {
            Thread writer = new Thread(this::writeLoop, "sabot-paint-probe");
            writer.setDaemon(true);
            writer.start();
        }
    }

    /** @return a probe writing to the file of {@value #PROPERTY}, or one that does nothing without it */
    public static PaintProbe fromSystemProperty() {
        String f = System.getProperty(PROPERTY);
        return f == null || f.isBlank() ? OFF : new PaintProbe(Paths.get(f));
    }

    /** UI thread, at the start of a paint: the paint's CPU time (apart from the wall time other processes stretch). */
    public void paintStarting() {
        if (file != null) {
            cpuAtStart = threads.getCurrentThreadCpuTime();
            queuedAtStart = runQueueWait();
        }
    }

    /**
     * UI thread, at the end of a paint.
     *
     * @param startNanos {@link System#nanoTime()} at the paint's start
     * @param copyNanos  of the paint's duration, the frame image's copy to the window (what the X server is sent)
     * @param robots     the robots the paint drew
     * @param fleet      the fleet service (observed for the notification breakdown), or null
     */
    public void painted(long startNanos, long copyNanos, List<RobotState> robots, FleetState fleet) {
        if (file == null) {
            return;
        }
        long duration = System.nanoTime() - startNanos;
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
