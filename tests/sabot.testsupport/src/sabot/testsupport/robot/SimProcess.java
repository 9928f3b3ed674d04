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

import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * A real {@code sabot-sim} process (onboard-bridge/build/sabot-sim, built by the reactor before the tests): the
 * robot's buses on ptys, ground truth in a CSV, and its control channel (a line protocol on loopback TCP) to place
 * obstacles, switch boards off and read the true pose.
 */
public final class SimProcess implements AutoCloseable {

    private static final Pattern LINK = Pattern.compile("\"link\": \"([^\"]+)\"");
    private static final Pattern CONTROL = Pattern.compile("\"control\": (\\d+)");
    private static final Pattern FIELD = Pattern.compile("(\\w+)=(-?[0-9.eE+-]+)");

    private final Process process;
    private final List<String> links = new ArrayList<>();
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
        Matcher m = LINK.matcher(firstLine);
        while (m.find()) {
            links.add(m.group(1));
        }
        Matcher c = CONTROL.matcher(firstLine);
        if (!c.find()) {
            throw new IllegalStateException("sabot-sim announced no control port: " + firstLine);
        }
        this.controlPort = Integer.parseInt(c.group(1));
    }

    /** @return the simulator binary, built by the reactor's onboard-bridge module */
    public static Path binary() {
        Path bin = PrivateXmppServer.repositoryRoot().resolve("onboard-bridge/build/sabot-sim");
        if (!Files.isExecutable(bin)) {
            throw new IllegalStateException(bin + " missing: build the reactor (make -C onboard-bridge build/sabot-sim)");
        }
        return bin;
    }

    /**
     * Starts the simulator on the lab map with one robot at {@code start} (x, y, θ) and waits for its announcement.
     *
     * @param dir   folder for the pty links and the truth file
     * @param extra further options, e.g. {@code --fault-crc 0.02}
     */
    public static SimProcess start(Path dir, double[] start, String... extra) throws IOException {
        Path map = PrivateXmppServer.repositoryRoot().resolve("onboard-bridge/maps/lab.yaml");
        Path truth = dir.resolve("truth.csv");
        List<String> cmd = new ArrayList<>(List.of(binary().toString(), "--map", map.toString(), "--start",
                String.format(Locale.ROOT, "%.3f,%.3f,%.4f", start[0], start[1], start[2]), "--seed", "7", "--link",
                dir.resolve("robot").toString(), "--truth", truth.toString(), "--control", "0"));
        cmd.addAll(List.of(extra));
        ProcessBuilder pb = new ProcessBuilder(cmd).redirectError(dir.resolve("sim.err").toFile());
        Process p = pb.start();
        BufferedReader out = new BufferedReader(new InputStreamReader(p.getInputStream(), StandardCharsets.UTF_8));
        String first = out.readLine();
        if (first == null) {
            throw new IOException("sabot-sim exited before announcing its buses: "
                    + Files.readString(dir.resolve("sim.err")));
        }
        Thread drain = new Thread(() -> {
            try {
                while (out.readLine() != null) {
                    // keep the pipe empty
                }
            } catch (IOException ended) {
                // process gone
            }
        }, "sabot-sim-stdout");
        drain.setDaemon(true);
        drain.start();
        return new SimProcess(p, first, truth);
    }

    /** @return the pty link of robot {@code n} (from 1): the serial device the onboard product opens */
    public String link(int n) {
        return links.get(n - 1);
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
        String answer = command("truth 1");
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
        process.destroy();
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
