package sabot.modbus;

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;

import com.google.gson.JsonObject;
import com.google.gson.JsonParser;

/**
 * A real {@code sabot-sim} process (onboard-bridge), one robot: its pty, its RTU-over-TCP port and its ground truth.
 * Built with make when missing or stale; stopped with SIGTERM.
 */
final class SimProcess implements AutoCloseable {

    private final Process process;
    private final String pty;
    private final int tcpPort;
    private final Path truth;

    private SimProcess(Process process, String pty, int tcpPort, Path truth) {
        this.process = process;
        this.pty = pty;
        this.tcpPort = tcpPort;
        this.truth = truth;
    }

    /** The repository root: system property sabot.root (set by the build), else the nearest parent with onboard-bridge. */
    static Path root() {
        String configured = System.getProperty("sabot.root");
        if (configured != null && Files.isDirectory(Paths.get(configured, "onboard-bridge"))) {
            return Paths.get(configured).toAbsolutePath();
        }
        for (Path p = Paths.get("").toAbsolutePath(); p != null; p = p.getParent()) {
            if (Files.isRegularFile(p.resolve("onboard-bridge/Makefile"))) {
                return p;
            }
        }
        throw new IllegalStateException("cannot find the repository root (onboard-bridge/Makefile); set -Dsabot.root");
    }

    /** @return the simulator binary, built by make if needed (make is a no-op when it is up to date) */
    static synchronized Path binary() throws IOException, InterruptedException {
        Path root = root();
        Process make = new ProcessBuilder("make", "-s", "-C", root.resolve("onboard-bridge").toString(),
                "build/sabot-sim").redirectErrorStream(true).start();
        String out = new String(make.getInputStream().readAllBytes(), StandardCharsets.UTF_8);
        if (make.waitFor() != 0) {
            throw new IOException("make build/sabot-sim failed:\n" + out);
        }
        return root.resolve("onboard-bridge/build/sabot-sim");
    }

    /**
     * Starts the simulator on the lab map with {@code extra} options and waits for its JSON line.
     *
     * @param dir where the pty link, the truth file and its stderr go
     */
    static SimProcess start(Path dir, String... extra) throws IOException, InterruptedException {
        Path truth = dir.resolve("truth.csv");
        List<String> cmd = new ArrayList<>(List.of(binary().toString(), "--map",
                root().resolve("onboard-bridge/maps/lab.yaml").toString(), "--tcp", "0", "--seed", "7", "--link",
                dir.resolve("robot").toString(), "--truth", truth.toString()));
        cmd.addAll(List.of(extra));
        Process p = new ProcessBuilder(cmd).redirectError(dir.resolve("sim.err").toFile()).start();
        BufferedReader out = new BufferedReader(new InputStreamReader(p.getInputStream(), StandardCharsets.UTF_8));
        CompletableFuture<String> first = CompletableFuture.supplyAsync(() -> {
            try {
                return out.readLine();
            } catch (IOException e) {
                return null;
            }
        });
        String line;
        try {
            line = first.get(10, TimeUnit.SECONDS);
        } catch (Exception e) {
            p.destroyForcibly();
            throw new IOException("sabot-sim printed no first line within 10 s: " + e, e);
        }
        if (line == null) {
            p.waitFor(5, TimeUnit.SECONDS);
            throw new IOException("sabot-sim exited: " + Files.readString(dir.resolve("sim.err")));
        }
        JsonObject robot = JsonParser.parseString(line).getAsJsonObject().getAsJsonArray("robots").get(0)
                .getAsJsonObject();
        return new SimProcess(p, robot.get("pty").getAsString(), robot.get("tcp").getAsInt(), truth);
    }

    String pty() {
        return pty;
    }

    int tcpPort() {
        return tcpPort;
    }

    Path truth() {
        return truth;
    }

    long pid() {
        return process.pid();
    }

    /** Sends SIGSTOP or SIGCONT: the simulator stops answering (and stops its clock) or goes on. */
    void signal(String name) throws IOException, InterruptedException {
        Process kill = new ProcessBuilder("kill", "-" + name, Long.toString(process.pid())).start();
        if (kill.waitFor() != 0) {
            throw new IOException("kill -" + name + " " + process.pid() + " failed");
        }
    }

    /** @return the data rows of the truth file, split (complete once the simulator has stopped) */
    List<String[]> truthRows() throws IOException {
        List<String[]> rows = new ArrayList<>();
        for (String line : Files.readAllLines(truth)) {
            String[] cols = line.split(",");
            if (cols.length == 12 && !cols[0].startsWith("t_s")) {
                rows.add(cols);
            }
        }
        return rows;
    }

    @Override
    public void close() throws InterruptedException {
        process.destroy(); // SIGTERM: the simulator removes its links and exits 0
        if (!process.waitFor(5, TimeUnit.SECONDS)) {
            process.destroyForcibly();
        }
    }
}
