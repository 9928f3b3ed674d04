package sabot.products;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.ArrayList;
import java.util.List;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * The workbench's start script and SABOT_WORKBENCH_BACKGROUND_NICE: 10 by default, 0 turns it off; set to N, a thread at
 * Thread.MIN_PRIORITY (the ControlML plug-in's and Smack's, LiveFleetUiTest checks those) and the JIT compilers run at
 * Linux nice N and every other thread at nice 0 (none above the UI thread, also as root); a bad value is refused
 * before Java starts. The JVM options are taken from the shipped script, run with a JAVA_HOME whose java only writes
 * down its arguments, and tried on this JDK with a small program that reads its threads' nice values from /proc.
 */
class WorkbenchPrioritiesTest {

    @TempDir
    Path dir;

    private record Run(int status, String output, List<String> javaArgs) {
    }

    /** The shipped start script with SABOT_WORKBENCH_BACKGROUND_NICE = {@code nice} (null: unset). */
    private Run script(String nice) throws IOException, InterruptedException {
        Path fakeHome = Files.createDirectories(dir.resolve("jdk/bin"));
        Path argsFile = dir.resolve("args");
        Files.deleteIfExists(argsFile);
        Path fakeJava = fakeHome.resolve("java");
        // as HotSpot does as a normal user with the policy: its warning on the error output (a line the script leaves
        // out), and a line of the workbench's own there
        Files.writeString(fakeJava, "#!/bin/sh\nprintf '%s\\n' \"$@\" > '" + argsFile + "'\n"
                + "echo 'OpenJDK 64-Bit Server VM warning: -XX:ThreadPriorityPolicy=1 may require system level "
                + "permission, e.g., being the root user. If the necessary permission is not possessed, changes to "
                + "priority will be silently ignored.' >&2\n" + "echo 'workbench: a line on the error output' >&2\n");
        Files.setPosixFilePermissions(fakeJava, PosixFilePermissions.fromString("rwxr-xr-x"));
        Path workbench = ProductProcess.product("sabot.workbench.product", "sabot-workbench");
        ProcessBuilder pb = new ProcessBuilder(workbench.resolve("sabot-workbench").toString(), "-consoleLog")
                .redirectErrorStream(true);
        pb.environment().put("JAVA_HOME", dir.resolve("jdk").toString());
        pb.environment().remove("SABOT_WORKBENCH_BACKGROUND_NICE");
        if (nice != null) {
            pb.environment().put("SABOT_WORKBENCH_BACKGROUND_NICE", nice);
        }
        Process s = pb.start();
        String out = new String(s.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
        int status = s.waitFor();
        return new Run(status, out, Files.exists(argsFile) ? Files.readAllLines(argsFile) : null);
    }

    @Test
    void onAtTenByDefaultOffAtZero() throws Exception {
        Run r = script(null);
        assertEquals(0, r.status(), r.output());
        assertTrue(r.javaArgs().containsAll(List.of("-XX:ThreadPriorityPolicy=1", "-XX:JavaPriority1_To_OSPriority=10",
                "-XX:CompilerThreadPriority=10")), r.javaArgs().toString());
        // the JVM's warning about raising priorities (which the maps never do) is left out, the rest passes
        assertFalse(r.output().contains("ThreadPriorityPolicy"), r.output());
        assertTrue(r.output().contains("workbench: a line on the error output"), r.output());

        Run off = script("0");
        assertEquals(0, off.status(), off.output());
        assertTrue(off.javaArgs().stream().noneMatch(a -> a.contains("Priority")), off.javaArgs().toString());
    }

    @Test
    void minPriorityThreadsAndTheCompilersRunAtTheNiceValueEveryOtherThreadAtZero() throws Exception {
        Run r = script("10");
        assertEquals(0, r.status(), r.output());
        List<String> options = r.javaArgs().stream().filter(a -> a.startsWith("-XX:")).toList();
        assertFalse(options.isEmpty(), "no -XX option: " + r.javaArgs());

        Path probe = dir.resolve("NiceProbe.java");
        Files.writeString(probe, """
                import java.nio.file.*;
                public class NiceProbe {
                    static int nice(Path task) throws Exception {
                        String s = Files.readString(task.resolve("stat"));
                        return Integer.parseInt(s.substring(s.lastIndexOf(')') + 2).split(" ")[16]);
                    }
                    static void report(String name) throws Exception {
                        System.out.println(name + " " + nice(Path.of("/proc/thread-self")));
                    }
                    public static void main(String[] a) throws Exception {
                        report("main");
                        for (int p : new int[] { Thread.MIN_PRIORITY, Thread.NORM_PRIORITY + 1, Thread.MAX_PRIORITY }) {
                            Thread t = new Thread(() -> { try { report("priority-" + p); } catch (Exception e) {
                                throw new RuntimeException(e); } });
                            t.setPriority(p);
                            t.start();
                            t.join();
                        }
                        try (var tasks = Files.list(Path.of("/proc/self/task"))) {
                            for (Path t : tasks.toList()) {
                                try {
                                    String comm = Files.readString(t.resolve("comm")).strip();
                                    if (comm.contains("CompilerThre") || comm.startsWith("GC Thread")
                                            || comm.equals("VM Thread")) {
                                        System.out.println(comm.replaceAll("[#0-9]+$", "") + " " + nice(t));
                                    }
                                } catch (NoSuchFileException ended) {
                                    // a thread that ended after the listing (the JVM adds and removes compiler threads)
                                } catch (java.io.IOException e) {
                                    // ended while its files were read ("No such process"); any other failure counts
                                    if (Files.exists(t)) {
                                        throw e;
                                    }
                                }
                            }
                        }
                    }
                }
                """);
        List<String> cmd = new ArrayList<>(List.of(Path.of(System.getProperty("java.home"), "bin", "java").toString()));
        cmd.addAll(options);
        cmd.add(probe.toString());
        Process p = new ProcessBuilder(cmd).redirectErrorStream(true).start();
        String report = new String(p.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
        assertEquals(0, p.waitFor(), report);
        // (as a normal user the JVM adds a warning line about the policy)
        List<String> lines = report.lines().filter(l -> !l.contains("warning")).sorted().distinct().toList();
        assertEquals(List.of("C1 CompilerThre 10", "C2 CompilerThre 10", "GC Thread 0", "VM Thread 0", "main 0",
                "priority-1 10", "priority-10 0", "priority-6 0"), lines, report);
    }

    @Test
    void aBadValueIsRefusedBeforeJavaStarts() throws Exception {
        for (String bad : new String[] { "20", "-1", "ten", "" }) {
            Run r = script(bad);
            if (bad.isEmpty()) {
                // empty is unset: the default
                assertEquals(0, r.status(), r.output());
                continue;
            }
            assertEquals(2, r.status(), bad + ": " + r.output());
            assertTrue(r.output().contains("SABOT_WORKBENCH_BACKGROUND_NICE must be a whole number from 0 to 19, not '"
                    + bad + "'"), r.output());
            assertEquals(null, r.javaArgs(), "java ran for " + bad);
        }
    }
}
