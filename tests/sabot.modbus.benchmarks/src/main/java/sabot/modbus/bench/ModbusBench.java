package sabot.modbus.bench;

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.time.Duration;
import java.util.Arrays;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.locks.LockSupport;

import com.google.gson.JsonObject;
import com.google.gson.JsonParser;

import sabot.modbus.BusSettings;
import sabot.modbus.ModbusBus;
import sabot.modbus.ModbusBuses;
import sabot.modbus.Parity;

/**
 * ./sabot bench modbus: transaction time of each kind of transaction against its computed wire time, on a real
 * sabot-sim. Transactions start on a fixed period (as a control loop issues them), so the line's inter-frame
 * silence has passed before each and the figure is the transaction itself: request out, answer in and decoded.
 */
public final class ModbusBench {

    private interface Op {
        void run() throws IOException;
    }

    private ModbusBench() {
    }

    public static void main(String[] args) throws Exception {
        int n = 2000;
        String via = "pty";
        double periodMs = 8;
        int retries = BusSettings.DEFAULT_RETRIES;
        for (int i = 0; i < args.length; i++) {
            switch (args[i]) {
                case "--transactions" -> n = Integer.parseInt(args[++i]);
                case "--via" -> via = args[++i];
                case "--period-ms" -> periodMs = Double.parseDouble(args[++i]);
                case "--retries" -> retries = Integer.parseInt(args[++i]);
                case "-h", "--help" -> {
                    System.out.println("usage: ./sabot bench modbus [--transactions N] [--via pty|tcp] [--period-ms P] [--retries R]");
                    return;
                }
                default -> {
                    System.err.println("sabot bench modbus: unknown option " + args[i]);
                    System.exit(2);
                }
            }
        }
        if (n < 10 || !(via.equals("pty") || via.equals("tcp")) || periodMs <= 0) {
            System.err.println("sabot bench modbus: --transactions >= 10, --via pty|tcp, --period-ms > 0");
            System.exit(2);
        }
        Path root = Paths.get(System.getProperty("sabot.root", ".")).toAbsolutePath();
        Path sim = root.resolve("onboard-bridge/build/sabot-sim");
        Path dir = Files.createTempDirectory("sabot-bench-modbus");
        Process p = new ProcessBuilder(sim.toString(), "--map", root.resolve("onboard-bridge/maps/lab.yaml").toString(),
                "--tcp", "0", "--seed", "1", "--link", dir.resolve("robot").toString())
                .redirectError(dir.resolve("sim.err").toFile()).start();
        try {
            String line = new BufferedReader(new InputStreamReader(p.getInputStream(), StandardCharsets.UTF_8))
                    .readLine();
            if (line == null) {
                throw new IOException("sabot-sim exited: " + Files.readString(dir.resolve("sim.err")));
            }
            JsonObject robot = JsonParser.parseString(line).getAsJsonObject().getAsJsonArray("robots").get(0)
                    .getAsJsonObject();
            BusSettings settings = via.equals("pty")
                    ? BusSettings.serial(robot.get("pty").getAsString()).withParity(Parity.NONE)
                    : BusSettings.tcp("127.0.0.1", robot.get("tcp").getAsInt());
            run(settings.withRetries(retries), n, (long) (periodMs * 1e6), via);
        } finally {
            p.destroy();
            p.waitFor(5, TimeUnit.SECONDS);
        }
    }

    private static void run(BusSettings settings, int n, long periodNanos, String via) throws IOException {
        try (ModbusBus bus = ModbusBuses.open(settings)) {
            double rate = 1.0; // rad/s: well inside the limit
            Map<String, Op> ops = new LinkedHashMap<>();
            Map<String, Duration> wire = new LinkedHashMap<>();
            ops.put("sact.readWheels", () -> bus.sact().readWheels());
            wire.put("sact.readWheels", bus.sact().readWheelsWireTime());
            ops.put("sact.setWheelSpeeds", () -> bus.sact().setWheelSpeeds(rate, rate));
            wire.put("sact.setWheelSpeeds", bus.sact().setWheelSpeedsWireTime());
            ops.put("ins.readMotion", () -> bus.ins().readMotion());
            wire.put("ins.readMotion", bus.ins().readMotionWireTime());
            ops.put("sonar.readSensor", () -> bus.sonar().readSensor(1));
            wire.put("sonar.readSensor", bus.sonar().readSensorWireTime());

            System.out.printf(Locale.ROOT, "command: ./sabot bench modbus --transactions %d --via %s --period-ms %.1f --retries %d%n",
                    n, via, periodNanos / 1e6, settings.retries());
            System.out.printf(Locale.ROOT, "bus: %s, %s, %s; one transaction started every %.1f ms%n",
                    settings.where(), settings.parity(), bus.timing(), periodNanos / 1e6);
            System.out.printf(Locale.ROOT, "%-22s %8s %8s %8s %8s %8s %7s%n", "transaction", "n", "p50 ms", "p99 ms",
                    "max ms", "wire ms", "p50/wire");
            StringBuilder json = new StringBuilder("{\"via\": \"" + via + "\", \"transactions\": " + n
                    + ", \"kinds\": {");
            long next = System.nanoTime();
            for (Map.Entry<String, Op> e : ops.entrySet()) {
                long[] t = new long[n];
                for (int i = -n / 10; i < n; i++) { // a tenth as warm-up (JIT), not counted
                    next += periodNanos;
                    for (long w = next - System.nanoTime(); w > 0; w = next - System.nanoTime()) {
                        LockSupport.parkNanos(w); // the control-loop period, not a synchronisation
                    }
                    long t0 = System.nanoTime();
                    e.getValue().run();
                    if (i >= 0) {
                        t[i] = System.nanoTime() - t0;
                    }
                }
                Arrays.sort(t);
                double p50 = t[n / 2] / 1e6;
                double p99 = t[(int) Math.ceil(n * 0.99) - 1] / 1e6;
                double max = t[n - 1] / 1e6;
                double w = wire.get(e.getKey()).toNanos() / 1e6;
                System.out.printf(Locale.ROOT, "%-22s %8d %8.3f %8.3f %8.3f %8.3f %7.2fx%n", e.getKey(), n, p50, p99,
                        max, w, p50 / w);
                json.append(String.format(Locale.ROOT,
                        "%s\"%s\": {\"p50_ms\": %.3f, \"p99_ms\": %.3f, \"max_ms\": %.3f, \"wire_ms\": %.3f, "
                                + "\"p50_ratio\": %.3f, \"p99_ratio\": %.3f}",
                        json.charAt(json.length() - 1) == '{' ? "" : ", ", e.getKey(), p50, p99, max, w, p50 / w,
                        p99 / w));
            }
            bus.sact().setWheelSpeeds(0, 0);
            var s = bus.statistics();
            System.out.printf(Locale.ROOT, "counters: %s%n", List.of(s.sact(), s.ins(), s.sonar()));
            System.out.println(json.append("}}"));
        }
    }
}
