package sabot.tools.simulate;

import java.io.IOException;
import java.io.PrintStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Locale;

import sabot.model.robot.RobotDescriptions;
import sabot.motion.sim.ControllerKind;
import sabot.motion.sim.Feedback;
import sabot.motion.sim.Scenario;
import sabot.motion.sim.Simulation;
import sabot.motion.sim.SimulationConfig;
import sabot.motion.sim.SimulationResult;

/**
 * {@code ./sabot simulate}: runs one scenario and prints, as its last line, one JSON object with the figures.
 *
 * <pre>
 * --scenario lemniscate|circle|square|offset|stabilize   (required)
 * --controller dfl|pseudoinverse                         (default dfl)
 * --feedback truth|odometry|ekf                          (default truth)
 * --seed N  --slip-noise P  --slip-bias P  --calibrated  --out DIR
 * --start crossing|vertex   (lemniscate and offset: where the figure-eight starts; default crossing)
 * --robot FILE              (robot-description properties; default: the reference robot)
 * </pre>
 * Bad input: one line {@code sabot simulate: error: ...} on stderr and exit status 2.
 */
public final class SimulateCommand {

    private SimulateCommand() {
    }

    public static void main(String[] args) {
        System.setProperty("java.awt.headless", "true");
        int status = run(args, System.out, System.err);
        System.exit(status);
    }

    /** @return the process exit status: 0 on success, 2 on bad input, 1 when the output cannot be written */
    public static int run(String[] args, PrintStream out, PrintStream err) {
        SimulationConfig config;
        Path outDir = null;
        try {
            Scenario scenario = null;
            ControllerKind controller = ControllerKind.DFL;
            Feedback feedback = Feedback.TRUTH;
            long seed = 1;
            double noise = 0;
            double bias = 0;
            boolean calibrated = false;
            boolean vertex = false;
            Path robotFile = null;
            for (int i = 0; i < args.length; i++) {
                String a = args[i];
                switch (a) {
                    case "--scenario" -> scenario = Scenario.parse(value(args, ++i, a));
                    case "--controller" -> controller = ControllerKind.parse(value(args, ++i, a));
                    case "--feedback" -> feedback = Feedback.parse(value(args, ++i, a));
                    case "--seed" -> seed = parseLong(value(args, ++i, a), a);
                    case "--slip-noise" -> noise = fraction(value(args, ++i, a), a);
                    case "--slip-bias" -> bias = fraction(value(args, ++i, a), a);
                    case "--calibrated" -> calibrated = true;
                    case "--out" -> outDir = Path.of(value(args, ++i, a));
                    case "--robot" -> robotFile = Path.of(value(args, ++i, a));
                    case "--start" -> {
                        String v = value(args, ++i, a);
                        if (!v.equals("crossing") && !v.equals("vertex")) {
                            throw new IllegalArgumentException("--start must be crossing or vertex, got '" + v + "'");
                        }
                        vertex = v.equals("vertex");
                    }
                    case "--help", "-h" -> {
                        out.println("usage: sabot simulate --scenario lemniscate|circle|square|offset|stabilize"
                                + " [--controller dfl|pseudoinverse] [--feedback truth|odometry|ekf] [--seed N]"
                                + " [--slip-noise P] [--slip-bias P] [--calibrated] [--out DIR] [--start crossing|vertex]"
                                + " [--robot FILE]");
                        return 0;
                    }
                    default -> throw new IllegalArgumentException("unknown option '" + a + "' (try --help)");
                }
            }
            if (scenario == null) {
                throw new IllegalArgumentException("--scenario is required (lemniscate|circle|square|offset|stabilize)");
            }
            config = SimulationConfig.of(scenario, controller, feedback).withSeed(seed).withSlip(noise, bias)
                    .withCalibrated(calibrated).withFromVertex(vertex);
            if (robotFile != null) {
                config = config.withRobot(RobotDescriptions.load(robotFile));
            }
        } catch (IllegalArgumentException e) { // includes InvalidRobotDescriptionException
            err.println("sabot simulate: error: " + e.getMessage());
            return 2;
        } catch (IOException e) {
            err.println("sabot simulate: error: cannot read robot description: " + e.getMessage());
            return 2;
        }
        SimulationResult result = Simulation.run(config);
        if (outDir != null) {
            try {
                Files.createDirectories(outDir);
                String stem = String.format(Locale.ROOT, "motion-%s-%s-%s", config.scenario().cliName(),
                        config.controller().cliName(), config.feedback().cliName());
                CsvOutput.write(result.trace(), outDir.resolve(stem + ".csv"));
                String title = String.format(Locale.ROOT, "%s, %s, %s feedback, slip noise %.3g, bias %.3g%s",
                        config.scenario().cliName(), config.controller().cliName(), config.feedback().cliName(),
                        config.slipNoise(), config.slipBias(), config.calibrated() ? ", calibrated" : "");
                Plots.writePath(result.trace(), title, outDir.resolve(stem + "-path.png"));
                Plots.writeError(result.trace(), title, outDir.resolve(stem + "-error.png"));
                out.println("wrote " + outDir.resolve(stem + ".csv") + " and " + stem + "-path.png, " + stem + "-error.png");
            } catch (IOException e) {
                err.println("sabot simulate: error: cannot write to " + outDir + ": " + e.getMessage());
                return 1;
            }
        }
        if (config.calibrated()) {
            var g = result.odometryGeometry();
            out.println(String.format(Locale.ROOT,
                    "UMBmark calibration: r_left %.6f m, r_right %.6f m (E_d %.6f), track %.6f m",
                    g.leftWheelRadius(), g.rightWheelRadius(), g.diameterRatio(), g.trackWidth()));
        }
        out.println(result.metrics().toJson(config));
        return 0;
    }

    private static String value(String[] args, int i, String option) {
        if (i >= args.length || args[i].startsWith("--")) {
            throw new IllegalArgumentException(option + " needs a value");
        }
        return args[i];
    }

    private static long parseLong(String v, String option) {
        try {
            return Long.parseLong(v);
        } catch (NumberFormatException e) {
            throw new IllegalArgumentException(option + " needs an integer, got '" + v + "'");
        }
    }

    private static double fraction(String v, String option) {
        double d;
        try {
            d = Double.parseDouble(v);
        } catch (NumberFormatException e) {
            throw new IllegalArgumentException(option + " needs a number (0.01 = 1 %), got '" + v + "'");
        }
        if (!Double.isFinite(d) || d < 0 || d > 0.5) {
            throw new IllegalArgumentException(option + " must be between 0 and 0.5 (0.01 = 1 %), got '" + v + "'");
        }
        return d;
    }
}
