package sabot.tools.simulate;

import java.io.IOException;
import java.io.PrintStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;

import sabot.model.robot.RobotDescription;
import sabot.model.robot.RobotDescriptions;
import sabot.motion.sim.ControllerKind;
import sabot.motion.sim.Feedback;
import sabot.motion.sim.OnboardLoop;
import sabot.motion.sim.Scenario;
import sabot.motion.sim.Simulation;
import sabot.motion.sim.SimulationConfig;
import sabot.motion.sim.SimulationResult;
import sabot.motion.sim.Trace;

/**
 * {@code ./sabot simulate}: runs one scenario and prints, as its last line, one JSON object with the figures.
 *
 * <pre>
 * --scenario lemniscate|circle|square|offset|stabilize|goal   (required)
 * --controller dfl|pseudoinverse                         (default dfl)
 * --feedback truth|odometry|ekf                          (default truth)
 * --seed N  --slip-noise P  --slip-bias P  --calibrated  --out DIR
 * --start crossing|vertex   (lemniscate and offset: where the figure-eight starts; default crossing)
 * --robot FILE              (robot-description properties; default: the reference robot)
 * </pre>
 * {@code --scenario goal} is the robot's own control loop ({@link OnboardLoop}: the motion task's loop with the
 * tasks' default settings, its planner, tracker and EKF) given the reference mission's goal; slip defaults to the
 * reference mission's (1 % noise, 0.2 % bias), and {@code --controller}, {@code --feedback}, {@code --calibrated} and
 * {@code --start} do not apply (the loop runs what the robot runs).
 * <p>
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

    /** The scenario name of the robot's own loop driven to the reference mission's goal. */
    static final String GOAL_SCENARIO = "goal";

    /** @return the process exit status: 0 on success, 2 on bad input, 1 when the output cannot be written */
    public static int run(String[] args, PrintStream out, PrintStream err) {
        SimulationConfig config;
        Path outDir = null;
        try {
            String scenario = null;
            ControllerKind controller = ControllerKind.DFL;
            Feedback feedback = Feedback.TRUTH;
            long seed = 1;
            Double noise = null;
            Double bias = null;
            boolean calibrated = false;
            boolean vertex = false;
            List<String> algorithmOptions = new ArrayList<>();
            Path robotFile = null;
            for (int i = 0; i < args.length; i++) {
                String a = args[i];
                switch (a) {
                    case "--scenario" -> scenario = value(args, ++i, a);
                    case "--controller" -> {
                        controller = ControllerKind.parse(value(args, ++i, a));
                        algorithmOptions.add(a);
                    }
                    case "--feedback" -> {
                        feedback = Feedback.parse(value(args, ++i, a));
                        algorithmOptions.add(a);
                    }
                    case "--seed" -> seed = parseLong(value(args, ++i, a), a);
                    case "--slip-noise" -> noise = fraction(value(args, ++i, a), a);
                    case "--slip-bias" -> bias = fraction(value(args, ++i, a), a);
                    case "--calibrated" -> {
                        calibrated = true;
                        algorithmOptions.add(a);
                    }
                    case "--out" -> outDir = Path.of(value(args, ++i, a));
                    case "--robot" -> robotFile = Path.of(value(args, ++i, a));
                    case "--start" -> {
                        String v = value(args, ++i, a);
                        if (!v.equals("crossing") && !v.equals("vertex")) {
                            throw new IllegalArgumentException("--start must be crossing or vertex, got '" + v + "'");
                        }
                        vertex = v.equals("vertex");
                        algorithmOptions.add(a);
                    }
                    case "--help", "-h" -> {
                        out.println("usage: sabot simulate --scenario lemniscate|circle|square|offset|stabilize"
                                + " [--controller dfl|pseudoinverse] [--feedback truth|odometry|ekf] [--seed N]"
                                + " [--slip-noise P] [--slip-bias P] [--calibrated] [--out DIR] [--start crossing|vertex]"
                                + " [--robot FILE]\n       sabot simulate --scenario goal [--seed N] [--slip-noise P]"
                                + " [--slip-bias P] [--out DIR] [--robot FILE]   (the robot's own control loop)");
                        return 0;
                    }
                    default -> throw new IllegalArgumentException("unknown option '" + a + "' (try --help)");
                }
            }
            if (scenario == null) {
                throw new IllegalArgumentException(
                        "--scenario is required (lemniscate|circle|square|offset|stabilize|goal)");
            }
            var robot = robotFile != null ? RobotDescriptions.load(robotFile) : RobotDescriptions.defaults();
            if (scenario.equals(GOAL_SCENARIO)) {
                if (!algorithmOptions.isEmpty()) {
                    throw new IllegalArgumentException(String.join(", ", algorithmOptions) + ": not for --scenario "
                            + GOAL_SCENARIO + " (the robot's loop runs the tracker task's DFL and its EKF)");
                }
                return goal(robot, seed, noise != null ? noise : OnboardLoop.REFERENCE_SLIP_NOISE,
                        bias != null ? bias : OnboardLoop.REFERENCE_SLIP_BIAS, outDir, out, err);
            }
            Scenario study;
            try {
                study = Scenario.parse(scenario);
            } catch (IllegalArgumentException e) {
                throw new IllegalArgumentException(e.getMessage() + " or " + GOAL_SCENARIO + " (the robot's loop)");
            }
            config = SimulationConfig.of(study, controller, feedback).withSeed(seed)
                    .withSlip(noise != null ? noise : 0, bias != null ? bias : 0).withCalibrated(calibrated)
                    .withFromVertex(vertex).withRobot(robot);
        } catch (IllegalArgumentException e) { // includes InvalidRobotDescriptionException
            err.println("sabot simulate: error: " + e.getMessage());
            return 2;
        } catch (IOException e) {
            err.println("sabot simulate: error: cannot read robot description: " + e.getMessage());
            return 2;
        }
        SimulationResult result = Simulation.run(config);
        if (outDir != null) {
            String stem = String.format(Locale.ROOT, "motion-%s-%s-%s", config.scenario().cliName(),
                    config.controller().cliName(), config.feedback().cliName());
            String title = String.format(Locale.ROOT, "%s, %s, %s feedback, slip noise %.3g, bias %.3g%s",
                    config.scenario().cliName(), config.controller().cliName(), config.feedback().cliName(),
                    config.slipNoise(), config.slipBias(), config.calibrated() ? ", calibrated" : "");
            if (!write(result.trace(), title, outDir, stem, out, err)) {
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

    /** The reference mission's goal, run by the robot's own loop. */
    private static int goal(RobotDescription robot, long seed, double noise, double bias, Path outDir,
            PrintStream out, PrintStream err) {
        OnboardLoop.Run run = OnboardLoop.toGoal(robot, OnboardLoop.REFERENCE_START, OnboardLoop.REFERENCE_GOAL,
                noise, bias, seed, OnboardLoop.REFERENCE_TIMEOUT);
        if (outDir != null) {
            String stem = "motion-goal-onboard";
            String title = String.format(Locale.ROOT, "the robot's loop to (3, 2, 90°), slip noise %.3g, bias %.3g",
                    noise, bias);
            if (!write(run.trace(), title, outDir, stem, out, err)) {
                return 1;
            }
        }
        out.println(run.toJson(seed, noise, bias));
        return 0;
    }

    private static boolean write(Trace trace, String title, Path outDir, String stem, PrintStream out,
            PrintStream err) {
        try {
            Files.createDirectories(outDir);
            CsvOutput.write(trace, outDir.resolve(stem + ".csv"));
            Plots.writePath(trace, title, outDir.resolve(stem + "-path.png"));
            Plots.writeError(trace, title, outDir.resolve(stem + "-error.png"));
            out.println("wrote " + outDir.resolve(stem + ".csv") + " and " + stem + "-path.png, " + stem
                    + "-error.png");
            return true;
        } catch (IOException e) {
            err.println("sabot simulate: error: cannot write to " + outDir + ": " + e.getMessage());
            return false;
        }
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
