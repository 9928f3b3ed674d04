package sabot.testsupport.process;

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.io.Reader;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.function.Consumer;
import java.util.function.Predicate;

/**
 * The console of a process under test, line by line, so that a test waits for the line that says something happened
 * instead of sleeping. Read by a thread of its own from the process's standard output ({@link #ofPipe}) or from the
 * file the console is redirected to ({@link #tail}, kept for a failed test). A wait ends with an
 * {@link AssertionError} holding the whole console when the line does not come in time or the process has ended and
 * every line it wrote has been seen.
 */
public final class ProcessConsole {

    /** How often a tail looks at the end of its file again: a file has no "line written" event to wait on. */
    private static final long TAIL_POLL_MS = 10;

    private final String name;
    private final Process process;
    private final List<String> lines = new ArrayList<>();
    /** Set by {@link #begin} before the console is handed out. */
    private Thread reader;

    private ProcessConsole(String name, Process process) {
        this.name = name;
        this.process = process;
    }

    private interface ThrowingPump {
        void run() throws IOException, InterruptedException;
    }

    /**
     * Reads the standard output of {@code process} (started with its error stream redirected into it, or to a file).
     *
     * @param name the process in failure messages, e.g. "the onboard product"
     * @param echo each line as it arrives (e.g. to the test's own output), or {@code l -> { }}
     */
    public static ProcessConsole ofPipe(String name, Process process, Consumer<String> echo) {
        ProcessConsole c = new ProcessConsole(name, process);
        return c.begin(() -> {
            try (BufferedReader r = new BufferedReader(new InputStreamReader(process.getInputStream(),
                    StandardCharsets.UTF_8))) {
                String line;
                while ((line = r.readLine()) != null) {
                    echo.accept(line);
                    c.add(line);
                }
            }
        });
    }

    /**
     * Tails {@code file}, where the console of {@code process} is redirected: a line is taken once its newline is
     * written; once the process has ended, what is left in the file is read and the tail ends.
     */
    public static ProcessConsole tail(String name, Process process, Path file) {
        ProcessConsole c = new ProcessConsole(name, process);
        return c.begin(() -> {
            try (Reader r = Files.newBufferedReader(file, StandardCharsets.UTF_8)) {
                StringBuilder partial = new StringBuilder();
                while (true) {
                    boolean ended = !process.isAlive();
                    int ch;
                    while ((ch = r.read()) >= 0) {
                        if (ch == '\n') {
                            c.add(partial.toString());
                            partial.setLength(0);
                        } else {
                            partial.append((char) ch);
                        }
                    }
                    if (ended) {
                        return;
                    }
                    TimeUnit.MILLISECONDS.sleep(TAIL_POLL_MS);
                }
            }
        });
    }

    private ProcessConsole begin(ThrowingPump pump) {
        reader = new Thread(() -> {
            try {
                pump.run();
            } catch (IOException | InterruptedException ended) {
                // the stream or file is gone, or the test is over
            } finally {
                synchronized (lines) {
                    lines.notifyAll();
                }
            }
        }, name + "-console");
        reader.setDaemon(true);
        reader.start();
        return this;
    }

    private void add(String line) {
        synchronized (lines) {
            lines.add(line);
            lines.notifyAll();
        }
    }

    /**
     * Waits for a console line matching {@code p}; one printed before the call counts.
     *
     * @param what for the failure message, e.g. "saying the XMPP session is online"
     * @return the line
     */
    public String await(Predicate<String> p, String what, long seconds) throws InterruptedException {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(seconds);
        int seen = 0;
        synchronized (lines) {
            while (true) {
                for (; seen < lines.size(); seen++) {
                    if (p.test(lines.get(seen))) {
                        return lines.get(seen);
                    }
                }
                long left = deadline - System.nanoTime();
                if (left <= 0 || !reader.isAlive() && seen == lines.size()) {
                    throw new AssertionError(name + ": no line " + what + " within " + seconds + " s; " + state()
                            + "; console:\n" + String.join("\n", lines));
                }
                TimeUnit.NANOSECONDS.timedWait(lines, left);
            }
        }
    }

    /** Waits until {@code count} console lines match {@code p} (e.g. the second login after a reconnection). */
    public void awaitCount(Predicate<String> p, int count, String what, long seconds) throws InterruptedException {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(seconds);
        synchronized (lines) {
            while (lines.stream().filter(p).count() < count) {
                long left = deadline - System.nanoTime();
                if (left <= 0 || !reader.isAlive()) {
                    throw new AssertionError(name + ": fewer than " + count + " lines " + what + " within " + seconds
                            + " s; " + state() + "; console:\n" + String.join("\n", lines));
                }
                TimeUnit.NANOSECONDS.timedWait(lines, left);
            }
        }
    }

    private String state() {
        return process.isAlive() ? "running" : "exit " + process.exitValue();
    }

    /** Waits at most {@code millis} for the console's last lines once the process has ended. */
    public void drain(long millis) throws InterruptedException {
        reader.join(millis);
    }

    /** @return the console lines so far */
    public List<String> lines() {
        synchronized (lines) {
            return List.copyOf(lines);
        }
    }

    /** @return the console so far, one string */
    public String output() {
        return String.join("\n", lines());
    }
}
