package sabot.onboard.internal;

import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.concurrent.TimeUnit;

/**
 * Puts the calling thread under the Linux real-time policy SCHED_FIFO, as ros2_control does for its controller
 * manager: a thread at a real-time priority preempts every ordinary (CFS) thread when it wakes, so the control loop
 * starts on time however busy the robot's other processes keep the CPU. Needs CAP_SYS_NICE (root, or
 * {@code LimitRTPRIO} in the service unit); without it the thread keeps the ordinary policy and the caller says why.
 * <p>
 * Java has no API for the policy; the thread finds its kernel id in {@code /proc/thread-self} and asks util-linux's
 * {@code chrt} to set it. Linux's real-time throttling (95 % of each second by default) keeps a runaway thread from
 * freezing the machine.
 */
public final class RealtimeScheduling {

    /** Highest SCHED_FIFO priority (Linux). */
    public static final int MAX_PRIORITY = 99;

    private RealtimeScheduling() {
    }

    /**
     * Applies SCHED_FIFO at {@code priority} to the calling thread.
     *
     * @param priority 1 … {@link #MAX_PRIORITY}
     * @return null when applied, otherwise why not (one line, for the log)
     */
    public static String applyToCurrentThread(int priority) {
        if (priority < 1 || priority > MAX_PRIORITY) {
            throw new IllegalArgumentException("real-time priority must be 1.." + MAX_PRIORITY + ", was " + priority);
        }
        String tid;
        try {
            // "/proc/thread-self" links to "PID/task/TID"
            tid = Files.readSymbolicLink(Path.of("/proc/thread-self")).getFileName().toString();
        } catch (IOException | UnsupportedOperationException e) {
            return "no /proc/thread-self (not Linux?): " + e.getMessage();
        }
        try {
            Process chrt = new ProcessBuilder("chrt", "--fifo", "--pid", Integer.toString(priority), tid)
                    .redirectErrorStream(true).start();
            if (!chrt.waitFor(5, TimeUnit.SECONDS)) {
                chrt.destroyForcibly();
                return "chrt did not answer within 5 s";
            }
            String out = new String(chrt.getInputStream().readAllBytes(), StandardCharsets.UTF_8).strip();
            return chrt.exitValue() == 0 ? null : "chrt: " + out.replace('\n', ' ');
        } catch (IOException e) {
            return "cannot run chrt (util-linux): " + e.getMessage();
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return "interrupted";
        }
    }

    /** @return the calling thread's scheduling policy as /proc shows it ("0" ordinary, "1" FIFO, "2" RR), or null */
    public static String currentPolicy() {
        try {
            String stat = Files.readString(Path.of("/proc/thread-self/stat"));
            String[] f = stat.substring(stat.lastIndexOf(')') + 2).split(" ");
            return f[38]; // field 41 (policy), counted from field 3 (state)
        } catch (IOException | RuntimeException e) {
            return null;
        }
    }
}
