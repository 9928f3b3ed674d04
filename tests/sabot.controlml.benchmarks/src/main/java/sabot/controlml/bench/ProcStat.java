package sabot.controlml.bench;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.util.ArrayList;
import java.util.List;

/** What the benchmarks read from Linux's {@code /proc/<pid>/stat} and {@code /proc/<pid>/task/<tid>/stat} (proc(5)). */
final class ProcStat {

    /** Index in {@link #fields} of utime (field 14 of proc(5)); stime follows. */
    private static final int UTIME = 11;
    /** Index in {@link #fields} of nice (field 19 of proc(5)). */
    private static final int NICE = 16;

    private ProcStat() {
    }

    /**
     * @param stat a stat file
     * @return its fields after the command name (which may hold spaces): index 0 is field 3 of proc(5), the state
     */
    static String[] fields(Path stat) throws IOException {
        String s = Files.readString(stat);
        return s.substring(s.lastIndexOf(')') + 2).split(" ");
    }

    /** @return the nice value in a process's or thread's stat file */
    static int nice(Path stat) throws IOException {
        return Integer.parseInt(fields(stat)[NICE]);
    }

    /** @return utime + stime in a process's stat file, ticks of 1/100 s */
    private static long ticks(Path stat) throws IOException {
        String[] f = fields(stat);
        return Long.parseLong(f[UTIME]) + Long.parseLong(f[UTIME + 1]);
    }

    /** @return utime + stime of this process alone (not its children), ticks of 1/100 s */
    static long ownCpuTicks() {
        try {
            return ticks(Paths.get("/proc/self/stat"));
        } catch (IOException e) {
            throw new IllegalStateException("/proc/self/stat: " + e.getMessage(), e);
        }
    }

    /** @return utime + stime of a process and its descendants, ticks of 1/100 s; 0 when it has ended */
    static long cpuTicks(long pid) {
        return sumOverTree(pid, p -> ticks(Paths.get("/proc", Long.toString(p), "stat")));
    }

    /**
     * @return the resident memory of a process and its descendants, kB: their proportional set sizes (Pss of proc(5)'s
     *         smaps_rollup: a page shared by n processes counts 1/n in each), so that memory they share (PostgreSQL's
     *         shared buffers) counts once; 0 when it has ended
     */
    static long rssKb(long pid) {
        return sumOverTree(pid, p -> {
            long kb = 0;
            for (String line : Files.readAllLines(Paths.get("/proc", Long.toString(p), "smaps_rollup"))) {
                if (line.startsWith("Pss:")) {
                    kb += Long.parseLong(line.replaceAll("[^0-9]", ""));
                }
            }
            return kb;
        });
    }

    /** A figure read from one process's files in /proc. */
    @FunctionalInterface
    private interface ProcFigure {
        long of(long pid) throws IOException;
    }

    /** @return {@code figure} summed over a process and its descendants (one that ends meanwhile counts 0) */
    private static long sumOverTree(long pid, ProcFigure figure) {
        ProcessHandle root = ProcessHandle.of(pid).orElse(null);
        if (root == null) {
            return 0;
        }
        List<ProcessHandle> tree = new ArrayList<>();
        tree.add(root);
        root.descendants().forEach(tree::add);
        long total = 0;
        for (ProcessHandle p : tree) {
            try {
                total += figure.of(p.pid());
            } catch (IOException | RuntimeException gone) {
                // ended meanwhile
            }
        }
        return total;
    }
}
