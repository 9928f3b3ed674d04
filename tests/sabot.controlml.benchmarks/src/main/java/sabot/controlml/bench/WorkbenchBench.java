package sabot.controlml.bench;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.nio.file.attribute.PosixFilePermissions;
import java.time.Instant;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.HashSet;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Set;
import java.util.TreeMap;
import java.util.TreeSet;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import java.util.stream.Collectors;

import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jxmpp.jid.EntityBareJid;

import sabot.controlml.ControlMlManager;
import sabot.controlml.Resources;
import sabot.testsupport.xmpp.PrivateXmppServer;
import sabot.tools.load.FleetLoad;

/**
 * {@code ./sabot bench workbench}: the real workbench product (a process, on the display it is given) against
 * {@link FleetLoad}'s robots, in a process of their own ({@link LoadProcess}), on a private Prosody or ejabberd.
 * <p>
 * Figures mode (default): the workbench runs with its paint probe ({@code sabot.workbench.paintProbe}); once every
 * robot has been drawn live and after a warm-up, a window of {@code --seconds} gives the Workspace view's paint time
 * (p50/p99/max, paints per second), the latency from a pose's time stamp to the end of the paint that first shows it,
 * its breakdown up to the fleet service's notification, and, as the reference for what the server costs, the same
 * items' latency at a second session of the operator's account that only receives them (the server's fan-out and
 * Smack's parsing, nothing of the workbench). Load average and CPU of the server, the workbench, the X server, the
 * load's process and this JVM beside them. The paint time's breakdown: the frame's copy to the window, the time the
 * UI thread was runnable but waited for a CPU (Linux schedstat) and the workbench's GC pauses in the window (its
 * {@value #GC_LOG}, epoch-stamped).
 * <p>
 * Memory mode ({@code --memory --minutes M}): no probe; every minute the workbench's heap after a full collection
 * ({@code jcmd GC.run}, then {@code GC.heap_info}) and its resident set; the growth slope by least squares.
 */
public final class WorkbenchBench {

    private int robots = 1;
    private PrivateXmppServer.Kind kind = PrivateXmppServer.Kind.PROSODY;
    private int seconds = 30;
    /**
     * Seconds between all robots live and the window: the JIT's warm-up. With 100 robots the compilers still take
     * ~22 % of a core 45 s after the start and ~3 % after 90 s (docs/WORKBENCH.md, "What limits it").
     */
    private int warmupSeconds = 90;
    private boolean memory;
    /** Where the processes run: {@code split} (default), {@code workbench-alone} or {@code shared}. */
    private String layout = "split";
    private int minutes = 60;
    private double rate = 10;
    /** Velocity telemetry rate, Hz; negative: as {@link #rate}. */
    private double velocityRate = -1;
    /** The load robots' rate while the workbench leases nothing faster; below 0: {@link #rate} (no leases needed). */
    private double baseRate = -1;
    private long seed = 1;
    private Path product;
    private Path out;
    private CpuLayout cpus = CpuLayout.shared("not placed yet");
    /** SABOT_WORKBENCH_BACKGROUND_NICE for the workbench's start script; null: unset, as the product ships. */
    private Integer backgroundNice;
    /**
     * The nice value of the load robots' process ({@link LoadProcess}): 19 has them use the CPU the workbench leaves
     * them, as robots on their own computers would.
     */
    private int loadNice;
    /** The workbench's JVM (a child of the product's start script), once started. */
    private long workbenchJvm = -1;

    public static void main(String[] args) throws Exception {
        WorkbenchBench b = new WorkbenchBench();
        try {
            b.parse(args);
        } catch (IllegalArgumentException e) {
            System.err.println("[bench] error: " + e.getMessage());
            System.exit(2);
        }
        System.exit(b.run());
    }

    private void parse(String[] args) {
        for (int i = 0; i < args.length; i++) {
            String a = args[i];
            String v = i + 1 < args.length ? args[i + 1] : null;
            switch (a) {
                case "--robots" -> { robots = positive(a, v, 1000); i++; }
                case "--server" -> { kind = FleetLoad.serverKind(need(a, v)); i++; }
                case "--seconds" -> { seconds = positive(a, v, 3600); i++; }
                case "--warmup" -> { warmupSeconds = positive(a, v, 600); i++; }
                case "--minutes" -> { minutes = positive(a, v, 24 * 60); i++; }
                case "--rate" -> { rate = Double.parseDouble(need(a, v)); i++; }
                case "--velocity-rate" -> { velocityRate = Double.parseDouble(need(a, v)); i++; }
                case "--base-rate" -> { baseRate = Double.parseDouble(need(a, v)); i++; }
                case "--seed" -> { seed = Long.parseLong(need(a, v)); i++; }
                case "--memory" -> memory = true;
                case "--shared-cpus" -> layout = "shared";
                case "--layout" -> {
                    layout = need(a, v);
                    if (!List.of("split", "workbench-alone", "shared").contains(layout)) {
                        throw new IllegalArgumentException("--layout '" + layout + "': expected split, "
                                + "workbench-alone or shared");
                    }
                    i++;
                }
                case "--background-nice" -> { backgroundNice = nice(a, v); i++; }
                case "--load-nice" -> { loadNice = nice(a, v); i++; }
                case "--product" -> { product = Paths.get(need(a, v)); i++; }
                case "--out" -> { out = Paths.get(need(a, v)); i++; }
                case "--help", "-h" -> {
                    System.out.println("usage: ./sabot bench workbench [--robots N (1)] [--server prosody|ejabberd] "
                            + "[--seconds S (30)] [--warmup S (90)] [--rate HZ (10)] [--velocity-rate HZ (= rate)] [--base-rate HZ (= rate; the robots' rate while the workbench leases nothing faster)] [--seed N (1)] [--layout split|workbench-alone|shared (split)] [--shared-cpus (= --layout shared)] [--background-nice N (0..19, 0: off; unset: as shipped)] [--load-nice N (0..19, 0)] "
                            + "| --memory [--robots N] [--minutes M (60)]");
                    System.exit(0);
                }
                default -> throw new IllegalArgumentException("unknown option " + a + " (--help)");
            }
        }
        if (product == null || !Files.isDirectory(product.resolve("plugins"))) {
            throw new IllegalArgumentException("--product: the workbench product's directory (with plugins/) is "
                    + "needed, got " + product);
        }
    }

    /** @return a Linux nice value given as {@code option}'s value, 0..19, or a precise error */
    private static int nice(String option, String v) {
        String n = need(option, v);
        if (!n.matches("[0-9]{1,2}") || Integer.parseInt(n) > 19) {
            throw new IllegalArgumentException(option + " '" + n + "': a Linux nice value, 0 to 19");
        }
        return Integer.parseInt(n);
    }

    private static String need(String option, String v) {
        if (v == null) {
            throw new IllegalArgumentException(option + " needs a value");
        }
        return v;
    }

    private static int positive(String option, String v, int max) {
        int n;
        try {
            n = Integer.parseInt(need(option, v));
        } catch (NumberFormatException e) {
            throw new IllegalArgumentException(option + " '" + v + "': expected a whole number");
        }
        if (n < 1 || n > max) {
            throw new IllegalArgumentException(option + " " + n + " is outside 1.." + max);
        }
        return n;
    }

    private int run() throws Exception {
        FleetLoad.setUpSmack();
        Path root = PrivateXmppServer.repositoryRoot();
        if (out == null) {
            out = root.resolve("target/bench-workbench");
        }
        String tag = (memory ? "memory-" : "") + kind.name().toLowerCase(Locale.ROOT) + "-" + robots;
        Path dir = out.resolve(tag);
        deleteTree(dir);
        Files.createDirectories(dir);
        Map<String, Object> figures = new LinkedHashMap<>();
        figures.put("server", kind.name().toLowerCase(Locale.ROOT));
        figures.put("robots", robots);
        figures.put("rate_hz", rate);
        figures.put("velocity_rate_hz", velocityRate < 0 ? rate : velocityRate);
        figures.put("base_rate_hz", baseRate < 0 ? rate : baseRate);
        figures.put("background_nice", backgroundNice == null ? "as shipped" : backgroundNice);
        figures.put("load_nice", loadNice);
        try (PrivateXmppServer server = PrivateXmppServer.of(kind).start()) {
            // the server on a CPU of its own, as in a deployment (it never shares the operator's desktop) and as
            // ./sabot bench controlml does; the load, the workbench (started by this JVM) and Xvfb on the others
            // --layout workbench-alone: the server and the load robots together, the workbench and Xvfb on the other
            // CPU, for a frame time the 100 clients do not take the workbench's CPU from
            CpuLayout cpus = switch (layout) {
                case "shared" -> CpuLayout.shared("--layout shared");
                case "workbench-alone" -> CpuLayout.workbenchAlone(server.pid(), CpuLayout.xServerPid());
                default -> CpuLayout.split(server.pid());
            };
            this.cpus = cpus;
            System.out.println("[bench] CPUs: " + cpus.description());
            figures.put("cpu_layout", cpus.description());
            String operatorPw = "operator-pw";
            EntityBareJid operator = server.register("operator", PrivateXmppServer.DOMAIN, operatorPw);
            server.registerAll(FleetLoad.accounts(robots, "load-", "robot-pw")); // in-band registration is closed
            long l0 = System.nanoTime();
            try (LoadProcess load = LoadProcess.start(server.port(), server.caFile(), loadNice, dir.resolve("load.log"), List.of(
                    "--robots", Integer.toString(robots), "--password", "robot-pw", "--operator", operator.toString(),
                    "--rate", Double.toString(rate), "--velocity-rate", Double.toString(velocityRate < 0 ? rate
                            : velocityRate), "--base-rate", Double.toString(baseRate < 0 ? rate : baseRate), "--seed",
                    Long.toString(seed)))) {
                System.out.printf(Locale.ROOT, "[bench] %s: %d load robots online in %.1f s (seed %d)%n", kind.name()
                        .toLowerCase(Locale.ROOT), robots, (System.nanoTime() - l0) / 1e9, seed);
                Path probe = dir.resolve("paint-probe.csv");
                Process wb = startWorkbench(dir, server, operator, operatorPw, load.jids(), memory ? null : probe);
                // stopped early (SIGTERM, Ctrl-C): the workbench goes with the benchmark
                Thread reaper = new Thread(wb::destroy);
                Runtime.getRuntime().addShutdownHook(reaper);
                try {
                    if (memory) {
                        memory(wb, dir, figures);
                    } else {
                        figures(wb, probe, server, operator, operatorPw, load, figures);
                    }
                } finally {
                    stop(wb);
                    Runtime.getRuntime().removeShutdownHook(reaper);
                }
            }
        }
        figures.put("load_avg_end", loadAverage());
        StringBuilder json = new StringBuilder("{");
        figures.forEach((k, v) -> json.append(json.length() > 1 ? ", " : "").append('"').append(k).append("\": ")
                .append(v instanceof String s ? "\"" + s + "\"" : v));
        System.out.println(json.append('}'));
        return 0;
    }

    // ------------------------------------------------------------------------------------------------ workbench

    private Process startWorkbench(Path dir, PrivateXmppServer server, EntityBareJid operator, String password,
            List<EntityBareJid> followed, Path probe) throws IOException, InterruptedException {
        // the account as ./sabot demo writes it: preferences of the workspace, the password in a 0600 file
        Path ws = dir.resolve("workspace");
        Path prefs = Files.createDirectories(ws.resolve(".metadata/.plugins/org.eclipse.core.runtime/.settings"));
        Files.writeString(prefs.resolve("sabot.workbench.prefs"), "eclipse.preferences.version=1\nxmpp.server=127.0.0.1"
                + "\nxmpp.port=" + server.port() + "\nxmpp.jid=" + operator + "\nxmpp.caFile=" + server.caFile()
                + "\nxmpp.robots=" + followed.stream().map(
                        Object::toString).collect(Collectors.joining(",")) + "\n");
        Path secrets = Files.createDirectories(dir.resolve("secrets"));
        Path pw = secrets.resolve("xmpp-password");
        Files.writeString(pw, password);
        Files.setPosixFilePermissions(pw, PosixFilePermissions.fromString("rw-------"));
        // the product as shipped: its start script, with the JVM options it sets (the thread priorities)
        List<String> cmd = new ArrayList<>(List.of(product.resolve("sabot-workbench").toString(), "-consoleLog",
                "-data", ws.toString(), "-vmargs", "-Dsabot.workbench.secrets=" + secrets));
        if (probe != null) {
            cmd.add("-D" + "sabot.workbench.paintProbe" + "=" + probe);
        }
        // the collector's pauses stop the UI thread too: logged with the epoch time to set them against the window
        cmd.add("-Xlog:gc:file=" + dir.resolve(GC_LOG) + ":timemillis");
        ProcessBuilder pb = new ProcessBuilder(cpus.wrap(cmd)).directory(product.toFile()).redirectErrorStream(true)
                .redirectOutput(dir.resolve("workbench.log").toFile());
        pb.environment().put("JAVA_HOME", System.getProperty("java.home"));
        if (backgroundNice != null) {
            pb.environment().put("SABOT_WORKBENCH_BACKGROUND_NICE", Integer.toString(backgroundNice));
        } else {
            pb.environment().remove("SABOT_WORKBENCH_BACKGROUND_NICE"); // the script's default
        }
        Process p = pb.start();
        workbenchJvm = jvmOf(p);
        System.out.printf("[bench] workbench pid %d (JVM %d), log %s%n", p.pid(), workbenchJvm, dir.resolve(
                "workbench.log"));
        return p;
    }

    /** The workbench's JVM: the start script's child (the script stays, to restart it on request). */
    private static long jvmOf(Process script) throws IOException, InterruptedException {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(30);
        while (System.nanoTime() < deadline) {
            var jvm = script.descendants().filter(h -> h.info().command().map(c -> c.endsWith("/java")).orElse(
                    false)).findFirst();
            if (jvm.isPresent()) {
                return jvm.get().pid();
            }
            if (script.waitFor(20, TimeUnit.MILLISECONDS)) {
                throw new IOException("the workbench's start script exited with status " + script.exitValue());
            }
        }
        throw new IOException("no workbench JVM under its start script (pid " + script.pid() + ") within 30 s");
    }

    /**
     * A process's threads by Linux nice value, names without their numbers: whether the priorities took effect (the
     * workbench's UI thread at 0, its telemetry ingest and JIT compilers at the start script's value; every thread of
     * the load's process at {@code --load-nice}).
     */
    static String threadsByNice(long pid) {
        Map<Integer, Set<String>> byNice = new TreeMap<>();
        try (var tasks = Files.list(Paths.get("/proc", Long.toString(pid), "task"))) {
            for (Path t : tasks.toList()) {
                try {
                    int nice = ProcStat.nice(t.resolve("stat"));
                    String name = Files.readString(t.resolve("comm")).strip().replaceAll("[#(]?[0-9]+\\)?$", "")
                            .strip();
                    byNice.computeIfAbsent(nice, k -> new TreeSet<>()).add(name);
                } catch (IOException | RuntimeException gone) {
                    // the thread ended meanwhile
                }
            }
        } catch (IOException e) {
            return "? (" + e.getMessage() + ")";
        }
        StringBuilder b = new StringBuilder();
        byNice.forEach((nice, names) -> b.append(b.isEmpty() ? "" : "; ").append(nice).append(": ").append(String
                .join(", ", names)));
        return b.toString();
    }

    /** Stops the start script and the workbench: SIGTERM, which the script passes on; then SIGKILL to both. */
    private static void stop(Process wb) throws InterruptedException {
        wb.destroy();
        if (!wb.waitFor(20, TimeUnit.SECONDS)) {
            // the JVM first: once the script is gone it is no longer its descendant
            wb.descendants().forEach(ProcessHandle::destroyForcibly);
            wb.destroyForcibly().waitFor(10, TimeUnit.SECONDS);
        }
    }

    /** Waits up to {@code seconds} for the workbench process; throws when it ended (it must outlive the run). */
    private static void hold(Process wb, double seconds) throws InterruptedException {
        if (wb.waitFor((long) (seconds * 1000), TimeUnit.MILLISECONDS)) {
            throw new IllegalStateException("the workbench exited with status " + wb.exitValue());
        }
    }

    // ------------------------------------------------------------------------------------------------ figures

    private void figures(Process wb, Path probe, PrivateXmppServer server, EntityBareJid operator, String password,
            LoadProcess load, Map<String, Object> figures) throws Exception {
        long started = System.nanoTime();
        long startedMicros = micros(Instant.now());
        // every robot drawn live once (the probe has a latency line for each), or the deadline: then the run goes
        // on with those that are, and says so
        int limitS = 60 + robots;
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(limitS);
        long firstMicros = -1;
        Set<String> live = new HashSet<>();
        long report = System.nanoTime();
        while (live.size() < robots && System.nanoTime() < deadline) {
            if (System.nanoTime() - report > 10_000_000_000L) {
                report = System.nanoTime();
                System.out.printf(Locale.ROOT, "[bench] %d of %d robots drawn live; telemetry acknowledged %d, failed %d "
                        + "(load %s)%n", live.size(), robots, load.telemetryPublished(), load.telemetryFailed(),
                        loadAverage());
            }
            hold(wb, 0.2);
            for (String line : lines(probe)) {
                if (line.startsWith("l,")) {
                    String[] f = line.split(",");
                    if (firstMicros < 0) {
                        firstMicros = Long.parseLong(f[1]);
                    }
                    live.add(f[3]);
                }
            }
        }
        if (live.isEmpty()) {
            throw new IllegalStateException("no robot drawn live within " + limitS + " s (see the workbench's log)");
        }
        if (live.size() < robots) {
            System.out.printf(Locale.ROOT, "[bench] only %d of %d robots drawn live within %d s; measuring with them%n",
                    live.size(), robots, limitS);
        }
        figures.put("robots_live", live.size());
        double allLiveS = (System.nanoTime() - started) / 1e9;
        System.out.printf(Locale.ROOT, "[figure] workbench process start to first live robot on screen %.2f s, to %d of "
                + "%d robots %.2f s (load %s)%n", (firstMicros - startedMicros) / 1e6, live.size(), robots, allLiveS,
                loadAverage());
        figures.put("start_to_first_live_s", round((firstMicros - startedMicros) / 1e6));
        figures.put("start_to_all_live_s", round(allLiveS));
        System.out.println("[bench] workbench threads by nice value: " + threadsByNice(workbenchJvm));
        System.out.printf("[bench] load robots' process %d (%s), its threads by nice value: %s%n", load.pid(), load
                .autogroup(), threadsByNice(load.pid()));

        // the reference: a second session of the operator that only receives cm.position (the server's fan-out
        // to one more session of the same account, and Smack's parsing), started once the workbench's
        // subscriptions are in place; its roster answers no subscription request (the workbench's session does)
        XMPPTCPConnection observer = new XMPPTCPConnection(server.configuration(operator.getLocalpart().toString(),
                PrivateXmppServer.DOMAIN, password).setResource("fanout-reference").build());
        Roster.getInstanceFor(observer).setSubscriptionMode(Roster.SubscriptionMode.manual);
        Window window = new Window();
        long[] ref = new long[(int) Math.min(50_000_000, robots * rate * (seconds + 30) + 1000)];
        AtomicLong refCount = new AtomicLong();
        ControlMlManager.getInstanceFor(observer).telemetry().addListener(Resources.POSITION, (device, p) -> {
            long now = micros(Instant.now());
            long stamp = micros(p.time());
            if (window.contains(stamp)) {
                long k = refCount.getAndIncrement();
                if (k < ref.length) {
                    ref[(int) k] = (now - stamp) * 1000;
                }
            }
        });
        observer.connect().login();
        for (EntityBareJid r : load.jids()) {
            ControlMlManager.getInstanceFor(observer).telemetry().follow(r, Resources.POSITION);
        }
        hold(wb, warmupSeconds);
        long acked0 = load.telemetryPublished();
        long failed0 = load.telemetryFailed();

        String load0 = loadAverage();
        long serverCpu0 = ProcStat.cpuTicks(server.pid());
        long wbCpu0 = ProcStat.cpuTicks(wb.pid());
        long xPid = CpuLayout.xServerPid();
        long xCpu0 = xPid < 0 ? 0 : ProcStat.cpuTicks(xPid);
        long loadCpu0 = ProcStat.cpuTicks(load.pid());
        long benchCpu0 = ProcStat.ownCpuTicks();
        long wall0 = System.nanoTime();
        long from = micros(Instant.now());
        window.open(from, from + seconds * 1_000_000L);
        hold(wb, seconds);
        long to = from + seconds * 1_000_000L;
        double wallS = (System.nanoTime() - wall0) / 1e9;
        double serverCpu = (ProcStat.cpuTicks(server.pid()) - serverCpu0) / wallS; // ticks of 1/100 s: per cent
        double wbCpu = (ProcStat.cpuTicks(wb.pid()) - wbCpu0) / wallS;
        double xCpu = xPid < 0 ? -1 : (ProcStat.cpuTicks(xPid) - xCpu0) / wallS;
        double loadCpu = (ProcStat.cpuTicks(load.pid()) - loadCpu0) / wallS;
        double benchCpu = (ProcStat.ownCpuTicks() - benchCpu0) / wallS;
        String load1 = loadAverage();
        // items stamped in the window still in flight reach the probe's file within its period: wait one more second
        hold(wb, 1.5);
        observer.instantShutdown();

        List<Long> frames = new ArrayList<>();
        List<Long> frameCpu = new ArrayList<>();
        List<Long> frameCopy = new ArrayList<>();
        List<Long> frameQueued = new ArrayList<>();
        List<Long> shown = new ArrayList<>();
        List<Long> notified = new ArrayList<>();
        for (String line : lines(probe)) {
            String[] f = line.split(",");
            if (f.length < 3) {
                continue;
            }
            long at = Long.parseLong(f[1]);
            long v = Long.parseLong(f[2]);
            switch (f[0]) {
                case "f" -> {
                    if (at >= from && at < to) {
                        frames.add(v);
                        if (f.length > 4) {
                            frameCpu.add(Long.parseLong(f[4]));
                        }
                        if (f.length > 5) {
                            frameCopy.add(Long.parseLong(f[5]));
                        }
                        if (f.length > 6 && Long.parseLong(f[6]) >= 0) {
                            frameQueued.add(Long.parseLong(f[6]));
                        }
                    }
                }
                // latencies: the item's stamp (at - v) in the window, as for the reference
                case "l" -> { if (stampIn(at, v, from, to)) shown.add(v); }
                case "n" -> { if (stampIn(at, v, from, to)) notified.add(v); }
                default -> { }
            }
        }
        long[] fr = sorted(frames);
        // a workbench whose connection dropped under the load paints nothing worth measuring: say so, not "no samples"
        List<String> dropped = lines(probe.resolveSibling("workbench.log")).stream().filter(l -> l.contains(
                "XMPP connection of") && l.contains("next attempt")).toList();
        if (!dropped.isEmpty()) {
            System.out.printf("[bench] the workbench's XMPP connection dropped %d time(s) during the run; first: %s%n",
                    dropped.size(), dropped.get(0));
        }
        if (fr.length == 0) {
            throw new IllegalStateException("the workbench painted no frame in the window" + (dropped.isEmpty() ? ""
                    : ", after its XMPP connection dropped") + " (see " + probe.resolveSibling("workbench.log") + ")");
        }
        long[] frCpu = sorted(frameCpu);
        long[] frCopy = sorted(frameCopy);
        long[] frQueued = sorted(frameQueued);
        long[] gcPauses = sorted(gcPauses(probe.resolveSibling(GC_LOG), from / 1000, to / 1000));
        long[] lat = sorted(shown);
        long[] note = sorted(notified);
        long[] refLat = Arrays.copyOf(ref, (int) Math.min(ref.length, refCount.get()));
        Arrays.sort(refLat);
        long published = Math.round(robots * rate * seconds);
        String loads = load0 + " → " + load1;
        System.out.printf(Locale.ROOT, "[figure] %s, %d robots, cm.position %.0f Hz, cm.velocity %.0f Hz, cm.mission 1 Hz, "
                + "%d s window, load %s%n", kind.name().toLowerCase(Locale.ROOT), robots, rate, velocityRate < 0 ? rate
                        : velocityRate, seconds, loads);
        System.out.printf(Locale.ROOT, "[figure] workspace paint time: %s, %.1f paints/s; its CPU time on the UI "
                + "thread: %s%n", pct(fr), fr.length / (double) seconds, pct(frCpu));
        System.out.printf(Locale.ROOT, "[figure]   of the paint time, the frame's copy to the window (the X server "
                + "reading the image): %s; the UI thread runnable, waiting for a CPU: %s; the workbench's GC pauses in "
                + "the window: %d, %.1f ms in all, max %.2f ms%n", pct(frCopy), pct(frQueued), gcPauses.length,
                Arrays.stream(gcPauses).sum() / 1e6, gcPauses.length == 0 ? 0 : gcPauses[gcPauses.length - 1] / 1e6);
        System.out.printf(Locale.ROOT, "[figure] telemetry-to-screen latency (pose stamp to end of the paint that "
                + "first shows it): %s; poses shown %d of ~%d published (%.1f %%)%n", pct(lat), lat.length, published,
                100.0 * lat.length / published);
        System.out.printf(Locale.ROOT, "[figure]   breakdown, pose stamp to the fleet service's notification in the "
                + "workbench: %s%n", pct(note));
        System.out.printf(Locale.ROOT, "[figure]   reference, server fan-out alone (the same items at a second session "
                + "of the operator, Smack only): %s, %d received%n", pct(refLat), refLat.length);
        System.out.printf(Locale.ROOT, "[figure]   CPU over the window (1 core = 100 %%): server %.0f %%, workbench "
                + "%.0f %%, X server %.0f %%, load robots %.0f %%, the reference session (this JVM) %.0f %%; robots' "
                + "publications in the window acknowledged %d, failed %d%n", serverCpu, wbCpu, xCpu, loadCpu, benchCpu,
                load.telemetryPublished() - acked0,
                load.telemetryFailed() - failed0);
        put(figures, "paint", fr);
        put(figures, "paint_cpu", frCpu);
        put(figures, "paint_copy", frCopy);
        put(figures, "paint_cpu_wait", frQueued);
        figures.put("gc_pauses", gcPauses.length);
        figures.put("gc_pause_total_ms", round(Arrays.stream(gcPauses).sum() / 1e6));
        figures.put("paints_per_s", round(fr.length / (double) seconds));
        put(figures, "latency", lat);
        figures.put("poses_shown_pct", round(100.0 * lat.length / published));
        put(figures, "notify", note);
        put(figures, "fanout", refLat);
        figures.put("server_cpu_pct", round(serverCpu));
        figures.put("workbench_cpu_pct", round(wbCpu));
        figures.put("x_server_cpu_pct", round(xCpu));
        figures.put("load_cpu_pct", round(loadCpu));
        figures.put("reference_cpu_pct", round(benchCpu));
        figures.put("load_avg", loads);
    }

    /** The workbench's GC log (in its run directory), one line a collection, stamped with the epoch time in ms. */
    static final String GC_LOG = "gc.log";
    private static final Pattern GC_PAUSE = Pattern.compile("^\\[(\\d+)ms\\].* Pause .* (\\d+\\.\\d+)ms$");

    /** @return the durations (ns) of the pauses the GC log holds that began in [{@code fromMs}, {@code toMs}) */
    static List<Long> gcPauses(Path log, long fromMs, long toMs) throws IOException {
        List<Long> pauses = new ArrayList<>();
        for (String line : lines(log)) {
            Matcher m = GC_PAUSE.matcher(line);
            if (m.find()) {
                long nanos = Math.round(Double.parseDouble(m.group(2)) * 1e6);
                long began = Long.parseLong(m.group(1)) - nanos / 1_000_000; // the stamp is the pause's end
                if (began >= fromMs && began < toMs) {
                    pauses.add(nanos);
                }
            }
        }
        return pauses;
    }

    private static boolean stampIn(long atMicros, long latencyNanos, long from, long to) {
        long stamp = atMicros - latencyNanos / 1000;
        return stamp >= from && stamp < to;
    }

    // ------------------------------------------------------------------------------------------------ memory

    private static final Pattern USED = Pattern.compile("used (\\d+)K");

    private void memory(Process wb, Path dir, Map<String, Object> figures) throws Exception {
        Path log = dir.resolve("workbench.log");
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(180);
        while (lines(log).stream().noneMatch(l -> l.contains("first live robot on screen"))) {
            if (System.nanoTime() > deadline) {
                throw new IllegalStateException("no live robot on the workbench's screen within 180 s (see " + log
                        + ")");
            }
            hold(wb, 0.2);
        }
        System.out.printf(Locale.ROOT, "[bench] memory: %d robots, sampling every minute for %d minutes (load %s)%n",
                robots, minutes, loadAverage());
        List<double[]> samples = new ArrayList<>(); // minute, heap MB after GC, RSS MB
        long t0 = System.nanoTime();
        for (int m = 0; m <= minutes; m++) {
            long due = t0 + TimeUnit.MINUTES.toNanos(m);
            long wait = due - System.nanoTime();
            if (wait > 0) {
                hold(wb, wait / 1e9);
            }
            double heap = heapAfterGc(workbenchJvm);
            double rss = rssMb(workbenchJvm);
            samples.add(new double[] { m, heap, rss });
            List<double[]> sofar = samples.size() > 6 ? samples.subList(5, samples.size()) : samples;
            System.out.printf(Locale.ROOT, "[memory] minute %3d: heap after full GC %.1f MB, RSS %.1f MB (load %s); "
                    + "slope so far %+.2f / %+.2f MB/h%n", m, heap, rss, loadAverage(), slope(sofar, 1) * 60, slope(
                            sofar, 2) * 60);
            Files.writeString(dir.resolve("memory.csv"), String.format(Locale.ROOT, "%d,%.2f,%.2f%n", m, heap, rss),
                    StandardCharsets.US_ASCII, java.nio.file.StandardOpenOption.CREATE,
                    java.nio.file.StandardOpenOption.APPEND);
        }
        // the first minutes hold the start's growth (classes, JIT, the map, the trails filling to their bound)
        List<double[]> steady = samples.size() > 6 ? samples.subList(5, samples.size()) : samples;
        double heapSlope = slope(steady, 1) * 60;
        double rssSlope = slope(steady, 2) * 60;
        System.out.printf(Locale.ROOT, "[figure] memory, %d robots, %d min: heap after GC %.1f → %.1f MB, RSS %.1f → "
                + "%.1f MB; slope from minute %d: heap %+.2f MB/h, RSS %+.2f MB/h%n", robots, minutes, samples.get(0)[1],
                samples.get(samples.size() - 1)[1], samples.get(0)[2], samples.get(samples.size() - 1)[2], (int) steady
                        .get(0)[0], heapSlope, rssSlope);
        figures.put("minutes", minutes);
        figures.put("heap_first_mb", round(samples.get(0)[1]));
        figures.put("heap_last_mb", round(samples.get(samples.size() - 1)[1]));
        figures.put("rss_first_mb", round(samples.get(0)[2]));
        figures.put("rss_last_mb", round(samples.get(samples.size() - 1)[2]));
        figures.put("heap_slope_mb_per_h", round(heapSlope));
        figures.put("rss_slope_mb_per_h", round(rssSlope));
    }

    private static double heapAfterGc(long pid) throws IOException, InterruptedException {
        jcmd(pid, "GC.run");
        String info = jcmd(pid, "GC.heap_info");
        Matcher m = USED.matcher(info);
        if (!m.find()) {
            throw new IllegalStateException("no 'used' in jcmd GC.heap_info: " + info);
        }
        return Long.parseLong(m.group(1)) / 1024.0;
    }

    private static String jcmd(long pid, String command) throws IOException, InterruptedException {
        Process p = new ProcessBuilder(Paths.get(System.getProperty("java.home"), "bin", "jcmd").toString(), Long
                .toString(pid), command).redirectErrorStream(true).start();
        String text = new String(p.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
        if (!p.waitFor(60, TimeUnit.SECONDS) || p.exitValue() != 0) {
            throw new IllegalStateException("jcmd " + pid + " " + command + " failed: " + text);
        }
        return text;
    }

    private static double rssMb(long pid) throws IOException {
        for (String l : Files.readAllLines(Paths.get("/proc", Long.toString(pid), "status"))) {
            if (l.startsWith("VmRSS:")) {
                return Long.parseLong(l.replaceAll("\\D+", "")) / 1024.0;
            }
        }
        throw new IllegalStateException("no VmRSS for " + pid);
    }

    /** Least-squares slope of column {@code col} against column 0. */
    static double slope(List<double[]> xs, int col) {
        int n = xs.size();
        if (n < 2) {
            return Double.NaN;
        }
        double mx = xs.stream().mapToDouble(a -> a[0]).average().orElse(0);
        double my = xs.stream().mapToDouble(a -> a[col]).average().orElse(0);
        double sxy = 0;
        double sxx = 0;
        for (double[] a : xs) {
            sxy += (a[0] - mx) * (a[col] - my);
            sxx += (a[0] - mx) * (a[0] - mx);
        }
        return sxy / sxx;
    }

    // ------------------------------------------------------------------------------------------------ helpers

    private static List<String> lines(Path f) throws IOException {
        return Files.exists(f) ? Files.readAllLines(f, StandardCharsets.ISO_8859_1) : List.of();
    }

    private static long[] sorted(List<Long> v) {
        return v.stream().mapToLong(Long::longValue).sorted().toArray();
    }

    private static String pct(long[] s) {
        if (s.length == 0) {
            return "no samples";
        }
        return String.format(Locale.ROOT, "p50 %.2f ms, p99 %.2f ms, max %.2f ms (n %d)", q(s, 0.5), q(s, 0.99),
                s[s.length - 1] / 1e6, s.length);
    }

    private static void put(Map<String, Object> figures, String name, long[] s) {
        figures.put(name + "_n", s.length);
        figures.put(name + "_p50_ms", s.length == 0 ? "null" : round(q(s, 0.5)));
        figures.put(name + "_p99_ms", s.length == 0 ? "null" : round(q(s, 0.99)));
        figures.put(name + "_max_ms", s.length == 0 ? "null" : round(s[s.length - 1] / 1e6));
    }

    private static double q(long[] sorted, double q) {
        int i = (int) Math.min(sorted.length - 1, Math.ceil(q * sorted.length) - 1);
        return sorted[Math.max(0, i)] / 1e6;
    }

    private static double round(double v) {
        return Math.round(v * 1000) / 1000.0;
    }

    private static long micros(Instant t) {
        return t.getEpochSecond() * 1_000_000L + t.getNano() / 1000;
    }

    private static String loadAverage() {
        try {
            return Files.readString(Paths.get("/proc/loadavg")).split(" ")[0];
        } catch (IOException e) {
            return "?";
        }
    }

    private static void deleteTree(Path dir) throws IOException {
        if (!Files.exists(dir)) {
            return;
        }
        try (var s = Files.walk(dir)) {
            for (Path p : s.sorted(java.util.Comparator.reverseOrder()).toList()) {
                Files.delete(p);
            }
        }
    }

    /** The measurement window in epoch microseconds; closed until opened. */
    private static final class Window {
        private volatile long start = Long.MAX_VALUE;
        private volatile long end = Long.MIN_VALUE;

        void open(long from, long to) {
            end = to;
            start = from;
        }

        boolean contains(long t) {
            return t >= start && t < end;
        }
    }
}
