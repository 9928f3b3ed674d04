package sabot.testsupport.robot;

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.io.PrintWriter;
import java.net.InetAddress;
import java.net.Socket;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import sabot.testsupport.process.ProcessConsole;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * A real {@code sabot-sim} process (onboard-bridge/build/sabot-sim) on the lab map: the robots' buses on ptys (and on
 * RTU-over-TCP ports when asked), ground truth in a CSV, and its control channel (a line protocol on loopback TCP) to
 * place obstacles, switch boards off and read the true pose. Stopped with SIGTERM.
 */
public final class SimProcess implements AutoCloseable {

    private static final Pattern LINK = Pattern.compile("\"link\": \"([^\"]+)\"");
    private static final Pattern PTY = Pattern.compile("\"pty\": \"([^\"]+)\"");
    private static final Pattern TCP = Pattern.compile("\"tcp\": (-?\\d+)");
    private static final Pattern CONTROL = Pattern.compile("\"control\": (\\d+)");
    /** How long the simulator may take to announce its buses (it opens ptys and ports, nothing slow). */
    private static final long ANNOUNCE_TIMEOUT_S = 10;
    private static final Pattern FIELD = Pattern.compile("(\\w+)=(-?[0-9.eE+-]+)");

    private final Process process;
    private final List<String> links = new ArrayList<>();
    private final List<String> ptys = new ArrayList<>();
    private final List<Integer> tcpPorts = new ArrayList<>();
    private final int controlPort;
    private final Path truth;
    private Socket control;
    private BufferedReader controlIn;
    private PrintWriter controlOut;

    /** The true state of one robot, from the simulator. */
    public record Truth(double t, double x, double y, double theta, double v, double omega, long contacts) {
        public double distanceTo(double gx, double gy) {
            return Math.hypot(gx - x, gy - y);
        }

        @Override
        public String toString() {
            return String.format(Locale.ROOT, "truth t=%.2f (%.3f, %.3f, %.3f) v=%.3f omega=%.3f contacts=%d", t, x,
                    y, theta, v, omega, contacts);
        }
    }

    private SimProcess(Process process, String firstLine, Path truth) {
        this.process = process;
        this.truth = truth;
        for (Matcher m = LINK.matcher(firstLine); m.find();) {
            links.add(m.group(1));
        }
        for (Matcher m = PTY.matcher(firstLine); m.find();) {
            ptys.add(m.group(1));
        }
        for (Matcher m = TCP.matcher(firstLine); m.find();) {
            tcpPorts.add(Integer.parseInt(m.group(1)));
        }
        Matcher c = CONTROL.matcher(firstLine);
        if (!c.find()) {
            throw new IllegalStateException("sabot-sim announced no control port: " + firstLine);
        }
        this.controlPort = Integer.parseInt(c.group(1));
    }

    /**
     * @return the simulator binary, built with make when missing or older than its sources (make is a no-op when it is
     *         up to date; the reactor's onboard-bridge module builds it before the tests)
     */
    public static synchronized Path binary() throws IOException {
        Path bridge = PrivateXmppServer.repositoryRoot().resolve("onboard-bridge");
        Process make = new ProcessBuilder("make", "-s", "-C", bridge.toString(), "build/sabot-sim")
                .redirectErrorStream(true).start();
        String out = new String(make.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
        try {
            if (make.waitFor() != 0) {
                throw new IOException("make build/sabot-sim failed:\n" + out);
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IOException("interrupted while building sabot-sim", e);
        }
        return bridge.resolve("build/sabot-sim");
    }

    /**
     * Starts the simulator on the lab map with one robot at {@code start} (x, y, θ) and waits for its announcement.
     *
     * @param dir   folder for the pty links and the truth file
     * @param extra further options, e.g. {@code --fault-crc 0.02}
     */
    public static SimProcess start(Path dir, double[] start, String... extra) throws IOException {
        List<String> options = new ArrayList<>(List.of("--start", String.format(Locale.ROOT, "%.3f,%.3f,%.4f",
                start[0], start[1], start[2])));
        options.addAll(List.of(extra));
        return launch(dir, options);
    }

    /**
     * Starts the simulator on the lab map (its own default start pose unless {@code options} has {@code --start}),
     * each robot's boards also on a Modbus RTU-over-TCP port ({@link #tcpPort()}), and waits for its announcement.
     *
     * @param dir     folder for the pty links, the truth file and the simulator's standard error
     * @param options further options, e.g. {@code --fault-crc 0.05}
     */
    public static SimProcess start(Path dir, String... options) throws IOException {
        List<String> all = new ArrayList<>(List.of("--tcp", "0"));
        all.addAll(List.of(options));
        return launch(dir, all, labMap());
    }

    /**
     * Starts the simulator on {@code map} (a ROS map_server YAML), the robots where {@code options} put them
     * ({@code --starts}), and waits for its announcement.
     */
    public static SimProcess startOnMap(Path dir, Path map, String... options) throws IOException {
        return launch(dir, List.of(options), map);
    }

    /** @return the lab map, the simulator's and the robots' unless a test says otherwise */
    public static Path labMap() {
        return PrivateXmppServer.repositoryRoot().resolve("onboard-bridge/maps/lab.yaml");
    }

    private static SimProcess launch(Path dir, List<String> options) throws IOException {
        return launch(dir, options, labMap());
    }

    private static SimProcess launch(Path dir, List<String> options, Path map) throws IOException {
        Path truth = dir.resolve("truth.csv");
        List<String> cmd = new ArrayList<>(List.of(binary().toString(), "--map", map.toString(), "--seed", "7",
                "--link", dir.resolve("robot").toString(), "--truth", truth.toString(), "--control", "0"));
        cmd.addAll(options);
        Path err = dir.resolve("sim.err");
        Process p = new ProcessBuilder(cmd).redirectError(err.toFile()).start();
        // its first line announces the buses; nothing else comes on its standard output
        ProcessConsole console = ProcessConsole.ofPipe("sabot-sim", p, line -> {
        });
        try {
            String first = console.await(line -> true, "announcing its buses", ANNOUNCE_TIMEOUT_S);
            return new SimProcess(p, first, truth);
        } catch (AssertionError | RuntimeException e) {
            p.destroyForcibly();
            throw new IOException(e.getMessage() + "\nsabot-sim's standard error:\n" + (Files.exists(err) ? Files
                    .readString(err) : ""), e);
        } catch (InterruptedException e) {
            p.destroyForcibly();
            Thread.currentThread().interrupt();
            throw new IOException("interrupted while sabot-sim started", e);
        }
    }

    /** @return the pty link of robot {@code n} (from 1): the serial device the onboard product opens */
    public String link(int n) {
        return links.get(n - 1);
    }

    /** @return the serial device of robot 1's boards (the pty itself, not its link) */
    public String pty() {
        return ptys.get(0);
    }

    /** @return robot 1's Modbus RTU-over-TCP port on loopback (started with {@link #start(Path, String...)}) */
    public int tcpPort() {
        int port = tcpPorts.get(0);
        if (port < 0) {
            throw new IllegalStateException("sabot-sim was started without --tcp");
        }
        return port;
    }

    /** @return the simulator's process id */
    public long pid() {
        return process.pid();
    }

    /** Sends SIGSTOP or SIGCONT: the simulator stops answering (and stops its clock) or goes on. */
    public void signal(String name) throws IOException, InterruptedException {
        Process kill = new ProcessBuilder("kill", "-" + name, Long.toString(process.pid())).start();
        if (kill.waitFor() != 0) {
            throw new IOException("kill -" + name + " " + process.pid() + " failed");
        }
    }

    /** @return the data rows of the truth file, split (complete once the simulator has stopped) */
    public List<String[]> truthRows() throws IOException {
        List<String[]> rows = new ArrayList<>();
        for (String line : Files.readAllLines(truth)) {
            String[] cols = line.split(",");
            if (cols.length == 12 && !cols[0].startsWith("t_s")) {
                rows.add(cols);
            }
        }
        return rows;
    }

    /** @return the truth CSV */
    public Path truthFile() {
        return truth;
    }

    /**
     * Sends one control-channel command and returns its answer line.
     *
     * @throws IOException when the simulator answers {@code error ...}
     */
    public synchronized String command(String line) throws IOException {
        if (control == null) {
            control = new Socket(InetAddress.getLoopbackAddress(), controlPort);
            control.setSoTimeout(5000);
            controlIn = new BufferedReader(new InputStreamReader(control.getInputStream(), StandardCharsets.UTF_8));
            controlOut = new PrintWriter(control.getOutputStream(), true, StandardCharsets.UTF_8);
        }
        controlOut.println(line);
        String answer = controlIn.readLine();
        if (answer == null) {
            throw new IOException("sabot-sim closed its control channel after '" + line + "'");
        }
        if (!answer.startsWith("ok")) {
            throw new IOException("sabot-sim refused '" + line + "': " + answer);
        }
        return answer;
    }

    /** @return robot 1's true state now */
    public Truth truth() throws IOException {
        return truth(1);
    }

    /** @return that robot's true state now (robots are numbered from 1) */
    public Truth truth(int robot) throws IOException {
        String answer = command("truth " + robot);
        double[] v = new double[7];
        String[] names = { "t", "x", "y", "theta", "v", "omega", "contacts" };
        Matcher m = FIELD.matcher(answer);
        while (m.find()) {
            for (int i = 0; i < names.length; i++) {
                if (names[i].equals(m.group(1))) {
                    v[i] = Double.parseDouble(m.group(2));
                }
            }
        }
        return new Truth(v[0], v[1], v[2], v[3], v[4], v[5], (long) v[6]);
    }

    /** @return the largest contact count of robot 1 in the truth file so far */
    public long contactsInTruthFile() throws IOException {
        long max = 0;
        for (String line : Files.readAllLines(truth)) {
            String[] f = line.split(",");
            if (f.length > 11 && f[1].equals("1")) {
                max = Math.max(max, Long.parseLong(f[11].trim()));
            }
        }
        return max;
    }

    @Override
    public void close() throws IOException {
        if (control != null) {
            control.close();
        }
        process.destroy(); // SIGTERM: the simulator removes its links and exits 0
        try {
            if (!process.waitFor(5, TimeUnit.SECONDS)) {
                process.destroyForcibly();
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            process.destroyForcibly();
        }
    }
}
