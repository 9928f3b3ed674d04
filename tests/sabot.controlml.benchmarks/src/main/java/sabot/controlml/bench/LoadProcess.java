package sabot.controlml.bench;

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.io.PrintStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.TimeUnit;

import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.impl.JidCreate;

import sabot.tools.load.FleetLoad;

/**
 * {@link FleetLoad}'s robots in a Java process of their own (its {@code --attach} mode on the benchmark's server),
 * started at a nice value: all of their threads, the collector's and the JIT's included, then take the CPU only as
 * that value gives it, apart from the benchmark's own threads (the reference session). The process inherits this
 * JVM's CPUs ({@link CpuLayout}).
 */
final class LoadProcess implements AutoCloseable {

    private final Process process;
    private final BufferedReader out;
    private final PrintStream in;
    private final List<EntityBareJid> jids;

    private LoadProcess(Process process, BufferedReader out, PrintStream in, List<EntityBareJid> jids) {
        this.process = process;
        this.out = out;
        this.in = in;
        this.jids = jids;
    }

    /**
     * Starts the robots and waits until they are online.
     *
     * @param caFile   the server's lab CA (PEM)
     * @param nice     the process's nice value, 0..19
     * @param log      where its standard error goes
     * @param arguments {@link FleetLoad}'s options after {@code --attach PORT --ca-file PEM}
     */
    static LoadProcess start(int port, Path caFile, int nice, Path log, List<String> arguments) throws IOException {
        // a session of its own: with Linux's autogroups (sched_autogroup_enabled) a session is one scheduling group,
        // whose nice value weighs all of its threads together (below)
        String java = Path.of(System.getProperty("java.home"), "bin", "java").toString();
        List<String> cmd = new ArrayList<>(List.of("setsid", "nice", "-n", Integer.toString(nice), java, "-Xss512k",
                "-cp", System.getProperty("java.class.path")));
        if (System.getProperty("sabot.root") != null) {
            cmd.add("-Dsabot.root=" + System.getProperty("sabot.root"));
        }
        cmd.addAll(List.of(FleetLoad.class.getName(), "--attach", Integer.toString(port), "--ca-file", caFile
                .toString()));
        cmd.addAll(arguments);
        Process p = new ProcessBuilder(cmd).redirectError(log.toFile()).start();
        BufferedReader out = new BufferedReader(new InputStreamReader(p.getInputStream(), StandardCharsets.UTF_8));
        PrintStream in = new PrintStream(p.getOutputStream(), true, StandardCharsets.UTF_8);
        try {
            String line;
            while ((line = out.readLine()) != null && !line.startsWith(FleetLoad.READY)) {
                // nothing else comes on its standard output (FleetLoad sends its log to standard error)
            }
            if (line == null) {
                throw new IOException("the load process exited (status " + p.waitFor() + ") before its robots were "
                        + "online: " + log);
            }
            List<EntityBareJid> jids = new ArrayList<>();
            for (String j : line.substring(FleetLoad.READY.length()).strip().split(",")) {
                jids.add(JidCreate.entityBareFrom(j));
            }
            // now in its own session for sure (setsid ran before java)
            autogroupNice(p.pid(), nice);
            return new LoadProcess(p, out, in, List.copyOf(jids));
        } catch (IOException | RuntimeException e) {
            p.destroyForcibly();
            throw e instanceof IOException io ? io : new IOException("load process: " + e.getMessage(), e);
        } catch (InterruptedException e) {
            p.destroyForcibly();
            Thread.currentThread().interrupt();
            throw new IOException("interrupted while the load robots came online", e);
        }
    }

    /**
     * Sets the nice value of the process's autogroup (sched(7)): the scheduler weighs the group as one task of that
     * value against the other sessions' groups, where a thread's own nice value only weighs it inside its group (200
     * threads at nice 19 weigh three times one thread at nice 0). Without autogroups the file is absent and the
     * threads' nice values are all there is.
     */
    private static void autogroupNice(long pid, int nice) throws IOException {
        Path autogroup = Path.of("/proc", Long.toString(pid), "autogroup");
        Path own = Path.of("/proc/self/autogroup");
        if (!java.nio.file.Files.exists(autogroup) || !java.nio.file.Files.exists(own)) {
            return;
        }
        // the group's name first: never the benchmark's own group (that would slow the workbench down with it)
        String group = java.nio.file.Files.readString(autogroup).split(" ")[0];
        if (group.equals(java.nio.file.Files.readString(own).split(" ")[0])) {
            throw new IOException("the load process " + pid + " shares the benchmark's autogroup " + group
                    + ": setsid did not give it a session of its own");
        }
        java.nio.file.Files.writeString(autogroup, Integer.toString(nice));
    }

    /** @return the process's autogroup line (sched(7)), e.g. {@code /autogroup-42 nice 19}; "none" without */
    String autogroup() {
        try {
            return java.nio.file.Files.readString(Path.of("/proc", Long.toString(process.pid()), "autogroup")).strip();
        } catch (IOException e) {
            return "none (" + e.getMessage() + ")";
        }
    }

    /** @return the process id */
    long pid() {
        return process.pid();
    }

    /** @return the robots' bare JIDs, in order */
    List<EntityBareJid> jids() {
        return jids;
    }

    /** @return the robots' telemetry publications the server acknowledged so far */
    long telemetryPublished() {
        return counts()[0];
    }

    /** @return the robots' telemetry publications that failed so far (refused, timed out or not sent) */
    long telemetryFailed() {
        return counts()[1];
    }

    /** @return the publications acknowledged and failed so far, asked of the process */
    private synchronized long[] counts() {
        in.println(FleetLoad.COUNTS);
        try {
            String line = out.readLine();
            if (line == null || !line.startsWith(FleetLoad.COUNTS)) {
                throw new IllegalStateException("the load process answered " + (line == null ? "nothing (it ended)"
                        : "'" + line + "'") + " to " + FleetLoad.COUNTS);
            }
            String[] f = line.substring(FleetLoad.COUNTS.length()).strip().split(" ");
            return new long[] { Long.parseLong(f[0]), Long.parseLong(f[1]) };
        } catch (IOException e) {
            throw new IllegalStateException("the load process: " + e.getMessage(), e);
        }
    }

    /** Closes the process's standard input (it stops its robots and exits); SIGKILL after 30 s. */
    @Override
    public void close() {
        in.close();
        try {
            if (!process.waitFor(30, TimeUnit.SECONDS)) {
                System.err.printf(Locale.ROOT, "[bench] the load process %d did not stop in 30 s: killed%n", process
                        .pid());
                process.destroyForcibly().waitFor(10, TimeUnit.SECONDS);
            }
        } catch (InterruptedException e) {
            process.destroyForcibly();
            Thread.currentThread().interrupt();
        }
    }
}
