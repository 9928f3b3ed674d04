package sabot.products;

import java.io.IOException;
import java.nio.file.DirectoryStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.function.Predicate;

import sabot.testsupport.process.ProcessConsole;

/**
 * A materialized product started the way ./sabot starts it ({@code java -jar plugins/org.eclipse.equinox.launcher_*.jar}),
 * with its console captured line by line so a test can wait for a log line instead of sleeping.
 */
final class ProductProcess implements AutoCloseable {

    static final long TIMEOUT_S = 60;

    private final Process process;
    private final ProcessConsole console;

    private ProductProcess(Process process) {
        this.process = process;
        this.console = ProcessConsole.ofPipe("product", process, line -> System.out.println("  | " + line));
    }

    /** @return the repository root (system property sabot.root, set by the pom) */
    static Path root() {
        return Paths.get(System.getProperty("sabot.root", "../..")).toAbsolutePath().normalize();
    }

    /** @return the materialized product folder of a product module, e.g. ("sabot.onboard.product", "sabot-onboard") */
    static Path product(String module, String uid) {
        Path p = root().resolve("product/" + module + "/target/products/" + uid + "/linux/gtk/x86_64");
        if (!Files.isDirectory(p.resolve("plugins"))) {
            throw new IllegalStateException("product not built: " + p + " (run the whole reactor)");
        }
        return p;
    }

    static ProductProcess start(Path productDir, List<String> extraVmArgs, List<String> args) throws IOException {
        List<String> cmd = new ArrayList<>();
        cmd.add(Paths.get(System.getProperty("java.home"), "bin", "java").toString());
        Path logback = productDir.resolve("etc/logback.xml");
        if (Files.isRegularFile(logback)) {
            cmd.add("-Dlogback.configurationFile=" + logback);
        }
        cmd.addAll(extraVmArgs);
        cmd.add("-jar");
        cmd.add(launcherJar(productDir).toString());
        cmd.add("-consoleLog");
        cmd.addAll(args);
        ProcessBuilder pb = new ProcessBuilder(cmd).directory(productDir.toFile()).redirectErrorStream(true);
        return new ProductProcess(pb.start());
    }

    /**
     * Starts a product through a start script of its own (e.g. sabot-workbench), in the product folder, with JAVA_HOME
     * set to this JVM's home so the script runs the same JDK as the tests.
     */
    static ProductProcess startScript(Path productDir, String script, List<String> args) throws IOException {
        List<String> cmd = new ArrayList<>();
        cmd.add(productDir.resolve(script).toString());
        cmd.addAll(args);
        ProcessBuilder pb = new ProcessBuilder(cmd).directory(productDir.toFile()).redirectErrorStream(true);
        pb.environment().put("JAVA_HOME", System.getProperty("java.home"));
        return new ProductProcess(pb.start());
    }

    static Path launcherJar(Path productDir) throws IOException {
        try (DirectoryStream<Path> s = Files.newDirectoryStream(productDir.resolve("plugins"),
                "org.eclipse.equinox.launcher_*.jar")) {
            for (Path p : s) {
                return p;
            }
        }
        throw new IllegalStateException("no Equinox launcher in " + productDir);
    }

    /** Waits until a console line matches; fails when the process ends first or after the timeout. */
    String await(Predicate<String> matcher, String what) throws InterruptedException {
        return console.await(matcher, what, TIMEOUT_S);
    }

    /**
     * Sends SIGTERM, as a service manager or {@code kill} does. Through the ProcessHandle: Process.destroy() would
     * also close our end of the console pipe and lose what the product logs while it stops.
     */
    void terminate() {
        process.toHandle().destroy();
    }

    /** Waits for the process to end and for its console to be read completely; returns the exit status. */
    int waitFor() throws InterruptedException {
        return waitFor(TIMEOUT_S);
    }

    /** {@link #waitFor()} with a longer limit, for a run that restarts the product. */
    int waitFor(long timeoutS) throws InterruptedException {
        if (!process.waitFor(timeoutS, TimeUnit.SECONDS)) {
            process.descendants().forEach(ProcessHandle::destroyForcibly);
            process.destroyForcibly();
            throw new AssertionError("product did not exit within " + timeoutS + " s; output:\n" + output());
        }
        console.drain(TimeUnit.SECONDS.toMillis(10));
        return process.exitValue();
    }

    List<String> lines() {
        return console.lines();
    }

    String output() {
        return console.output();
    }

    @Override
    public void close() {
        process.descendants().forEach(ProcessHandle::destroyForcibly); // a start script's JVM
        if (process.isAlive()) {
            process.destroyForcibly();
        }
    }
}
