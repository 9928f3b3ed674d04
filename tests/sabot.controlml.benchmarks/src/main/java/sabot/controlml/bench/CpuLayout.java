package sabot.controlml.bench;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;

/**
 * Where the benchmark's processes run: the server on a CPU of its own and the benchmark's clients (one JVM) on the
 * others, as in a deployment, where the server never shares a CPU with the robots and workbenches it serves. The
 * usual practice of latency benchmarks (the load generator apart from the system under test); on a machine with two
 * CPUs, sharing them let the clients' threads and the server's event loop preempt each other, which spread the
 * round-trip ratio over 1.29–1.46 from run to run (docs/CONTROLML.md, section 12).
 *
 * <p>Set with {@code taskset(1)} (util-linux) on every thread of both processes and of the server's descendants
 * (ejabberd runs beam.smp under its control script); threads started later inherit their creator's CPUs.
 */
final class CpuLayout {

    private final String description;
    /** CPUs for the processes this JVM starts afterwards (taskset's list), or null: this JVM's. */
    private final String startedCpus;

    private CpuLayout(String description) {
        this(description, null);
    }

    private CpuLayout(String description, String startedCpus) {
        this.description = description;
        this.startedCpus = startedCpus;
    }

    /**
     * @param command a process to start
     * @return the command run on the CPUs this layout gives to the processes this JVM starts ({@code taskset -c}), or
     *         the command itself when they share this JVM's
     */
    List<String> wrap(List<String> command) {
        if (startedCpus == null) {
            return command;
        }
        List<String> out = new ArrayList<>(List.of("taskset", "-c", startedCpus));
        out.addAll(command);
        return out;
    }

    /** @return how the processes were placed, for the report, e.g. {@code server cpu 1, clients cpu 0} */
    String description() {
        return description;
    }

    /** Leaves every process on every CPU. */
    static CpuLayout shared(String why) {
        return new CpuLayout("shared (" + why + ")");
    }

    /** The CPUs this JVM may use and the server's process tree; or, when the layout cannot be made, why. */
    private record Placement(List<Integer> allowed, List<Long> serverTree, CpuLayout refused) {

        static Placement of(long serverPid) {
            List<Integer> allowed;
            try {
                allowed = parseCpuList(run("taskset", "-pc", Long.toString(ProcessHandle.current().pid())));
            } catch (IOException | IllegalArgumentException e) {
                return failed(CpuLayout.shared("taskset: " + e.getMessage()));
            }
            if (allowed.size() < 2) {
                return failed(CpuLayout.shared(allowed.size() + " CPU"));
            }
            ProcessHandle server = ProcessHandle.of(serverPid).filter(ProcessHandle::isAlive).orElse(null);
            if (server == null) {
                return failed(CpuLayout.shared("no server process " + serverPid));
            }
            List<Long> tree = new ArrayList<>();
            tree.add(serverPid);
            server.descendants().forEach(d -> tree.add(d.pid()));
            return new Placement(allowed, tree, null);
        }

        private static Placement failed(CpuLayout refused) {
            return new Placement(null, null, refused);
        }

        /** Gives every allowed CPU back to {@code pids}, so that the report's "shared" holds after a failure. */
        CpuLayout undo(List<Long> pids, Exception why) {
            for (long pid : pids) {
                try {
                    run("taskset", "-a", "-p", "-c", join(allowed), Long.toString(pid));
                } catch (IOException gone) {
                    // ended meanwhile
                }
            }
            return CpuLayout.shared("taskset: " + why.getMessage());
        }
    }

    /**
     * Puts the server (and its descendants) on the last CPU this JVM may use and this JVM on the others.
     *
     * @return the layout, or {@link #shared} with the reason when fewer than two CPUs are allowed or taskset fails
     */
    static CpuLayout split(long serverPid) {
        Placement p = Placement.of(serverPid);
        if (p.refused() != null) {
            return p.refused();
        }
        int server = p.allowed().get(p.allowed().size() - 1);
        String clients = join(p.allowed().subList(0, p.allowed().size() - 1));
        try {
            for (long pid : p.serverTree()) {
                run("taskset", "-a", "-p", "-c", Integer.toString(server), Long.toString(pid));
            }
            // taskset -a exits 0 for a process that ended meanwhile: read the server's CPUs back
            if (!parseCpuList(run("taskset", "-pc", Long.toString(serverPid))).equals(List.of(server))) {
                throw new IOException("the server did not move to cpu " + server);
            }
            run("taskset", "-a", "-p", "-c", clients, Long.toString(ProcessHandle.current().pid()));
        } catch (IOException | IllegalArgumentException e) {
            return p.undo(p.serverTree(), e);
        }
        return new CpuLayout("server cpu " + server + ", clients cpu " + clients);
    }

    /**
     * For a frame time without the load generator on the workbench's CPU: the server and this JVM (the reference
     * session, and the load robots' process it starts, which inherits its CPUs) on the last CPU, the processes this
     * JVM starts later with {@link #wrap} (the workbench) and the X server on the others.
     *
     * @param serverPid the server's process
     * @param xServerPid the X server's process, or -1 when unknown (then it stays where it is, and the description
     *                   says so)
     * @return the layout, or {@link #shared} with the reason when fewer than two CPUs are allowed or taskset fails
     */
    static CpuLayout workbenchAlone(long serverPid, long xServerPid) {
        Placement p = Placement.of(serverPid);
        if (p.refused() != null) {
            return p.refused();
        }
        String load = Integer.toString(p.allowed().get(p.allowed().size() - 1));
        String workbench = join(p.allowed().subList(0, p.allowed().size() - 1));
        List<Long> moved = new ArrayList<>(p.serverTree());
        moved.add(ProcessHandle.current().pid());
        String x = "X server not found";
        try {
            for (long pid : moved) {
                run("taskset", "-a", "-p", "-c", load, Long.toString(pid));
            }
            if (xServerPid > 0 && ProcessHandle.of(xServerPid).isPresent()) {
                run("taskset", "-a", "-p", "-c", workbench, Long.toString(xServerPid));
                x = "X server cpu " + workbench;
            }
        } catch (IOException | IllegalArgumentException e) {
            return p.undo(moved, e);
        }
        return new CpuLayout("server and load cpu " + load + ", workbench cpu " + workbench + ", " + x, workbench);
    }

    /**
     * The X server of this process's display: the pid in {@code /tmp/.X<n>-lock} for {@code DISPLAY=:<n>}.
     *
     * @return its pid, or -1 without a local display or lock file
     */
    static long xServerPid() {
        String display = System.getenv("DISPLAY");
        if (display == null || !display.matches(":\\d+(\\.\\d+)?")) {
            return -1;
        }
        String n = display.substring(1).replaceFirst("\\..*", "");
        try {
            return Long.parseLong(java.nio.file.Files.readString(java.nio.file.Paths.get("/tmp/.X" + n + "-lock"))
                    .strip());
        } catch (IOException | NumberFormatException e) {
            return -1;
        }
    }

    /**
     * Parses the list of {@code taskset -pc}'s answer ({@code pid 42's current affinity list: 0,2-3}).
     *
     * @throws IllegalArgumentException when the answer has no list
     */
    static List<Integer> parseCpuList(String tasksetAnswer) {
        int colon = tasksetAnswer.lastIndexOf(':');
        if (colon < 0) {
            throw new IllegalArgumentException("no affinity list in \"" + tasksetAnswer.strip() + "\"");
        }
        List<Integer> cpus = new ArrayList<>();
        for (String part : tasksetAnswer.substring(colon + 1).strip().split(",")) {
            int dash = part.indexOf('-');
            int first = Integer.parseInt(dash < 0 ? part : part.substring(0, dash));
            int last = dash < 0 ? first : Integer.parseInt(part.substring(dash + 1));
            for (int c = first; c <= last; c++) {
                cpus.add(c);
            }
        }
        return cpus;
    }

    private static String join(List<Integer> cpus) {
        StringBuilder sb = new StringBuilder();
        for (int c : cpus) {
            sb.append(sb.length() == 0 ? "" : ",").append(c);
        }
        return sb.toString();
    }

    private static String run(String... command) throws IOException {
        Process p = new ProcessBuilder(command).redirectErrorStream(true).start();
        try {
            String out = new String(p.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
            if (!p.waitFor(10, TimeUnit.SECONDS) || p.exitValue() != 0) {
                throw new IOException(String.join(" ", command) + " failed: " + out.strip());
            }
            return out;
        } catch (InterruptedException e) {
            p.destroy();
            Thread.currentThread().interrupt();
            throw new IOException("interrupted: " + String.join(" ", command));
        }
    }
}
