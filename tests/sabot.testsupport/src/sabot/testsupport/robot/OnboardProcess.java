package sabot.testsupport.robot;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.TimeUnit;
import java.util.function.Predicate;
import java.util.stream.Stream;

import sabot.testsupport.process.ProcessConsole;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * The materialized Sabot Onboard product as a process, started as {@code ./sabot onboard --config FILE} starts it,
 * configured for one simulated robot: the bus on the simulator's pty, the lab map, the ControlML account on a private
 * server. Its console is captured so that tests wait for log lines instead of sleeping.
 */
public final class OnboardProcess implements AutoCloseable {

    public static final long TIMEOUT_S = 60;

    private final Process process;
    private final Path config;
    private final ProcessConsole console;

    private OnboardProcess(Process process, Path config, Path log) {
        this.process = process;
        this.config = config;
        this.console = ProcessConsole.tail("onboard product", process, log);
    }

    /**
     * The settings of one robot's configuration file.
     *
     * The robot's roles come from its server's shared groups (the configuration's defaults): a test grants them with
     * {@code PrivateXmppServer.grant}.
     *
     * @param caFile the lab CA of the XMPP server (a private server's {@code caFile()}); null: the JVM's trust store
     */
    public record Robot(String name, String pty, double[] start, int xmppPort, Path caFile) {
    }

    /** The tasks a robot's configuration enables unless its extra lines set {@code tasks} themselves. */
    public static final String TASKS = "bus, localizer, planner, tracker, teleop, motion, controlml, remotefs";

    /**
     * @return the configuration text for a robot, the tasks {@link #TASKS} enabled, on the lab map, plus {@code extra}
     *         lines (a {@code tasks = ...} or {@code planner.map = ...} line among them replaces the default one)
     */
    public static String configuration(Robot r, Path passwordFile, Path fsRoot, String extra) {
        return configuration(r, passwordFile, fsRoot, extra, "127.0.0.1");
    }

    /**
     * As {@link #configuration(Robot, Path, Path, String)}, the robot's XMPP server(s) given: {@code controlml.server}
     * (e.g. a cluster's nodes, {@code 127.0.0.1, 127.0.0.2})
     */
    public static String configuration(Robot r, Path passwordFile, Path fsRoot, String extra, String servers) {
        String map = PrivateXmppServer.repositoryRoot().resolve("onboard-bridge/maps/lab.yaml").toString();
        String tasks = "tasks = " + TASKS;
        StringBuilder rest = new StringBuilder();
        for (String line : extra.split("\\R", -1)) {
            if (line.matches("\\s*tasks\\s*=.*")) {
                tasks = line.strip();
            } else if (line.matches("\\s*planner\\.map\\s*=.*")) {
                map = line.substring(line.indexOf('=') + 1).strip();
            } else {
                rest.append(line).append('\n');
            }
        }
        return String.format(Locale.ROOT, """
                robot.name = %s
                %s
                bus.port = %s
                bus.parity = NONE
                localizer.startX = %.3f
                localizer.startY = %.3f
                localizer.startTheta = %.4f
                planner.map = %s
                controlml.server = %s
                controlml.port = %d
                controlml.caFile = %s
                controlml.jid = %s@%s
                controlml.passwordFile = %s
                remotefs.root = %s
                %s
                """, r.name(), tasks, r.pty(), r.start()[0], r.start()[1], r.start()[2], map, servers, r.xmppPort(), r.caFile() == null ? "" : r.caFile(), r.name(),
                PrivateXmppServer.DOMAIN, passwordFile, fsRoot, rest.toString().strip());
    }

    /** Writes the password file (mode 0600) and the configuration into {@code dir}, then starts the product. */
    public static OnboardProcess start(Path dir, Robot robot, String password, String extra) throws IOException {
        return start(dir, robot, password, extra, "127.0.0.1");
    }

    /** As {@link #start(Path, Robot, String, String)}, with the robot's XMPP server(s) given ({@code servers}). */
    public static OnboardProcess start(Path dir, Robot robot, String password, String extra, String servers)
            throws IOException {
        return start(writeConfiguration(dir, robot, password, extra, servers));
    }

    /**
     * As {@link #start(Path, Robot, String, String)}, the framework's configuration area in {@code dir/osgi} instead
     * of the product's {@code configuration/} (as {@code ./sabot demo} runs each robot): Config Admin persists the
     * tasks' configurations there, so that several robots started from the one product folder at once do not read
     * each other's.
     */
    public static OnboardProcess startWithOwnArea(Path dir, Robot robot, String password, String extra)
            throws IOException {
        return start(writeConfiguration(dir, robot, password, extra, "127.0.0.1"), dir.resolve("osgi"));
    }

    private static Path writeConfiguration(Path dir, Robot robot, String password, String extra, String servers)
            throws IOException {
        Path passwordFile = dir.resolve("xmpp-password");
        Files.writeString(passwordFile, password + "\n");
        Files.setPosixFilePermissions(passwordFile, PosixFilePermissions.fromString("rw-------"));
        Path fsRoot = Files.createDirectories(dir.resolve("fs"));
        Path config = dir.resolve("onboard.conf");
        Files.writeString(config, configuration(robot, passwordFile, fsRoot, extra, servers));
        return config;
    }

    /** Starts the product with a configuration file as it is. */
    public static OnboardProcess start(Path config) throws IOException {
        return start(config, null);
    }

    /**
     * @param osgiArea the framework's configuration area ({@code -configuration}), or null for the product's own
     */
    private static OnboardProcess start(Path config, Path osgiArea) throws IOException {
        Path product = product();
        List<String> cmd = new ArrayList<>();
        cmd.add(Paths.get(System.getProperty("java.home"), "bin", "java").toString());
        cmd.addAll(jvmOptions(product));
        cmd.add("-Dlogback.configurationFile=" + product.resolve("etc/logback.xml"));
        cmd.add("-jar");
        cmd.add(launcherJar(product).toString());
        cmd.add("-consoleLog");
        cmd.add("-config");
        cmd.add(config.toString());
        if (osgiArea != null) {
            cmd.add("-configuration");
            cmd.add(osgiArea.toString());
        }
        // the console goes to a file beside the configuration (kept for a failed test) and is tailed from there
        Path log = config.resolveSibling("onboard.log");
        ProcessBuilder pb = new ProcessBuilder(cmd).directory(product.toFile()).redirectErrorStream(true)
                .redirectOutput(log.toFile());
        return new OnboardProcess(pb.start(), config, log);
    }

    /** @return the product's etc/jvm.options (as ./sabot onboard reads them): one option a line, # comments */
    public static List<String> jvmOptions(Path product) throws IOException {
        Path file = product.resolve("etc/jvm.options");
        if (!Files.isRegularFile(file)) {
            return List.of();
        }
        return Files.readAllLines(file).stream().map(l -> l.replaceFirst("#.*", "").strip()).filter(l -> !l
                .isEmpty()).toList();
    }

    public static Path product() {
        Path p = PrivateXmppServer.repositoryRoot().resolve(
                "product/sabot.onboard.product/target/products/sabot-onboard/linux/gtk/x86_64");
        if (!Files.isDirectory(p.resolve("plugins"))) {
            throw new IllegalStateException("onboard product not built: " + p + " (run the whole reactor)");
        }
        return p;
    }

    private static Path launcherJar(Path product) throws IOException {
        try (Stream<Path> s = Files.list(product.resolve("plugins"))) {
            return s.filter(p -> p.getFileName().toString().matches("org\\.eclipse\\.equinox\\.launcher_.*\\.jar"))
                    .findFirst().orElseThrow(() -> new IllegalStateException("no launcher in " + product));
        }
    }

    /**
     * Waits for a console line matching {@code p} (one already printed counts).
     *
     * @param what for the failure message, e.g. "the robot's XMPP login"
     */
    public String await(Predicate<String> p, String what) throws InterruptedException {
        return await(p, what, TIMEOUT_S);
    }

    public String await(Predicate<String> p, String what, long seconds) throws InterruptedException {
        return console.await(p, what, seconds);
    }

    /** Waits until {@code count} console lines match {@code p} (e.g. the second login after a reconnection). */
    public void awaitCount(Predicate<String> p, int count, String what) throws InterruptedException {
        console.awaitCount(p, count, what, TIMEOUT_S);
    }

    /** @return the console so far */
    public String output() {
        return console.output();
    }

    /** @return the configuration file */
    public Path config() {
        return config;
    }

    /** SIGTERM, then wait for the exit status. */
    public int stop() throws InterruptedException {
        process.destroy();
        if (!process.waitFor(TIMEOUT_S, TimeUnit.SECONDS)) {
            process.destroyForcibly();
            throw new AssertionError("onboard product did not stop within " + TIMEOUT_S + " s:\n" + output());
        }
        console.drain(TimeUnit.SECONDS.toMillis(5)); // the console's last lines, not yet read
        return process.exitValue();
    }

    /** @return the exit status, waiting for the process to end */
    public int waitFor() throws InterruptedException {
        if (!process.waitFor(TIMEOUT_S, TimeUnit.SECONDS)) {
            throw new AssertionError("onboard product still running after " + TIMEOUT_S + " s:\n" + output());
        }
        console.drain(TimeUnit.SECONDS.toMillis(5)); // the console's last lines, not yet read
        return process.exitValue();
    }

    @Override
    public void close() {
        if (process.isAlive()) {
            process.destroy();
            try {
                if (!process.waitFor(20, TimeUnit.SECONDS)) {
                    process.destroyForcibly();
                }
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                process.destroyForcibly();
            }
        }
    }
}
