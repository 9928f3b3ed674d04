package sabot.onboard.motion.internal;

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
            tid = threadId();
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

    /**
     * Sets the calling thread's timer slack: how much later than asked the kernel may end its timed waits so as to
     * group wake-ups (50 µs for an ordinary thread; none under SCHED_FIFO). A thread may set its own through
     * {@code /proc/TID/timerslack_ns} without privilege; other threads keep theirs.
     *
     * @param nanos the slack, ≥ 1 ns
     * @return null when applied, otherwise why not (one line, for the log)
     */
    public static String applyTimerSlackToCurrentThread(long nanos) {
        if (nanos < 1) {
            throw new IllegalArgumentException("timer slack must be at least 1 ns, was " + nanos);
        }
        try {
            Files.writeString(Path.of("/proc", threadId(), "timerslack_ns"), Long.toString(nanos));
            return null;
        } catch (IOException | UnsupportedOperationException e) {
            return "cannot set the timer slack (Linux 4.6 or later): " + e.getMessage();
        }
    }

    /** @return the calling thread's timer slack in ns, or -1 when /proc does not tell */
    public static long currentTimerSlack() {
        try {
            return Long.parseLong(Files.readString(Path.of("/proc", threadId(), "timerslack_ns")).strip());
        } catch (IOException | RuntimeException e) {
            return -1;
        }
    }

    /** @return the calling thread's kernel id: "/proc/thread-self" links to "PID/task/TID" */
    private static String threadId() throws IOException {
        return Files.readSymbolicLink(Path.of("/proc/thread-self")).getFileName().toString();
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
