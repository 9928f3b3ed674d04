package sabot.planner.benchmarks;

import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.io.PrintWriter;
import java.lang.management.ManagementFactory;
import java.lang.management.ThreadMXBean;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;

import sabot.model.geometry.Point2D;
import sabot.model.map.Cell;
import sabot.model.map.GridGeometry;
import sabot.model.map.MapServerFormat;
import sabot.planner.CostModel;
import sabot.planner.PlanResult;
import sabot.planner.Planner;
import sabot.planner.Planners;
import sabot.planner.internal.LpnNavigationFunction;
import sabot.planner.internal.PlanningGrid;
import sabot.tools.grids.BenchmarkGrids;

/**
 * Times ROS navfn and Sabot's planners, alternating, on the grids of {@link BenchmarkGrids}:
 * {@code ./sabot bench navfn --navigation CHECKOUT} (tools/bench-navfn builds navfn's driver; this class drives it over
 * its standard input). Three questions, each asked of both planners with the same start and goal:
 * <ul>
 * <li><b>whole</b>: the navigation function over the whole reachable grid and the path from the start (navfn
 * {@code calcNavFnDijkstra(false)} from the goal; Sabot {@code lpn}, one thread);</li>
 * <li><b>plan</b>: the robot's question, start to goal (navfn as {@code NavfnROS::makePlan} calls it:
 * {@code calcNavFnDijkstra(true)} propagating from the robot, stopped when the goal cell has a value; Sabot
 * {@code lpn-focused} by default);</li>
 * <li><b>field</b>: the whole-grid navigation function alone, without a path (navfn's {@code setupNavFn(true)} and
 * {@code propNavFnDijkstra} as {@code calcNavFnDijkstra(false)} calls them; Sabot's {@code LpnNavigationFunction}
 * {@code compute} from the goal, as {@code lpn} runs it before its descent).</li>
 * </ul>
 * Each round runs a batch of calls per grid and question, navfn then Sabot in odd rounds and the other way round in
 * even ones; the first round warms both up and is not counted. Reported: the best round's median per call (best of
 * rounds) and the median of all counted calls, of the wall-clock time and of the CPU time of the calling thread (on a
 * shared machine the wall clock also counts the time other processes held the core; both sides measure the same
 * calls the same way: {@code clock_gettime(CLOCK_THREAD_CPUTIME_ID)} in the driver, {@link ThreadMXBean} here); path
 * costs are Sabot's cost integral ({@link CostModel#pathCost}) of both paths.
 *
 * <p>Each grid and question is measured in a JVM of its own (this class again, with the same JVM options), as a robot
 * runs one planner on its map: in one JVM the hot loop is compiled with the branch profile of whichever grid ran
 * first, and the others pay for it (on the 2-core VM, maze-1000's navigation function 24 ms alone, 31-33 ms after
 * random-100, random-1000 and random-2000; docs/PLANNER.md). {@code --one-jvm} measures everything in this JVM instead.
 */
public final class NavfnComparison {

    private record Sample(List<Double> roundMedians, List<Double> all) {
        Sample() {
            this(new ArrayList<>(), new ArrayList<>());
        }

        void add(double[] times) {
            double[] sorted = times.clone();
            Arrays.sort(sorted);
            roundMedians.add(NavfnComparison.median(sorted));
            for (double t : times) {
                all.add(t);
            }
        }

        double best() {
            return roundMedians.stream().mapToDouble(Double::doubleValue).min().orElse(Double.NaN);
        }

        double median() {
            return NavfnComparison.median(all.stream().mapToDouble(Double::doubleValue).sorted().toArray());
        }
    }

    private record Outcome(long reached, double pathCost, double pathLength) {
    }

    /**
     * The "field" question's Sabot side: the whole-grid navigation function alone
     * ({@code LpnNavigationFunction.compute}, as {@code lpn} runs it before its descent), on the grid synced once, from
     * the goal cell.
     */
    private static final class Field {
        private final LpnNavigationFunction function = new LpnNavigationFunction(CostModel.standard());
        private final int[] goals;

        Field(BenchmarkGrids.Scenario scenario) {
            PlanningGrid grid = new PlanningGrid();
            function.gridChanged(grid, grid.sync(scenario.costmap()));
            Cell goal = scenario.costmap().geometry().cellAt(scenario.goal()).orElseThrow();
            goals = new int[] {grid.index(goal.column(), goal.row())};
        }

        void compute() {
            function.compute(goals, -1);
        }

        long reached() {
            return function.finalizedCount();
        }
    }

    /**
     * Samples (wall clock and CPU time) and outcomes by key {@code grid/question/navfn|sabot}; a child JVM writes them
     * to its standard output, one per line, and the parent reads them back (doubles as {@link Double#toString}, which
     * reads back exactly).
     */
    private static final class Results {
        final Map<String, Sample> wall = new LinkedHashMap<>();
        final Map<String, Sample> cpu = new LinkedHashMap<>();
        final Map<String, Outcome> outcomes = new LinkedHashMap<>();

        void write(java.io.PrintStream out) {
            write(out, "wall", wall);
            write(out, "cpu", cpu);
            outcomes.forEach((key, o) -> out.println("outcome " + key + " " + o.reached() + " " + o.pathCost() + " "
                    + o.pathLength()));
            out.flush();
        }

        private static void write(java.io.PrintStream out, String clock, Map<String, Sample> samples) {
            samples.forEach((key, sample) -> out.println("sample " + clock + " " + key + " "
                    + join(sample.roundMedians()) + " " + join(sample.all())));
        }

        private static String join(List<Double> values) {
            return String.join(",", values.stream().map(String::valueOf).toList());
        }

        void read(BufferedReader in) throws IOException {
            for (String line = in.readLine(); line != null; line = in.readLine()) {
                String[] fields = line.split(" ");
                if (fields[0].equals("sample") && fields.length == 5) {
                    Sample sample = new Sample(split(fields[3]), split(fields[4]));
                    (fields[1].equals("wall") ? wall : cpu).put(fields[2], sample);
                } else if (fields[0].equals("outcome") && fields.length == 5) {
                    outcomes.put(fields[1], new Outcome(Long.parseLong(fields[2]), Double.parseDouble(fields[3]),
                            Double.parseDouble(fields[4])));
                } else {
                    throw new IOException("unexpected line from a measuring JVM: " + line);
                }
            }
        }

        private static List<Double> split(String values) {
            List<Double> list = new ArrayList<>();
            for (String value : values.split(",")) {
                list.add(Double.parseDouble(value));
            }
            return list;
        }
    }

    private static final ThreadMXBean THREAD = ManagementFactory.getThreadMXBean();
    /** Internal option: measure in this JVM and write the results for the parent (see {@link Results}). */
    private static final String CHILD = "--child-jvm";
    /** The questions, in the order they are asked per grid and printed. */
    private static final List<String> QUESTIONS = List.of("whole", "plan", "field");

    private NavfnComparison() {
    }

    public static void main(String[] args) throws IOException, InterruptedException {
        Path navfn = null;
        int rounds = 5;
        List<String> grids = List.of("random-100", "random-1000", "random-2000", "maze-1000", "enclosed-1000");
        String wholePlanner = "lpn";
        String planPlanner = "lpn-focused";
        List<String> questions = QUESTIONS;
        boolean oneJvm = false;
        boolean child = false;
        for (int i = 0; i < args.length; i++) {
            switch (args[i]) {
                case "--navfn" -> navfn = Path.of(args[++i]);
                case "--rounds" -> rounds = Integer.parseInt(args[++i]);
                case "--grids" -> grids = List.of(args[++i].split(","));
                case "--whole" -> wholePlanner = args[++i];
                case "--plan" -> planPlanner = args[++i];
                case "--questions" -> questions = List.of(args[++i].split(","));
                case "--one-jvm" -> oneJvm = true;
                case CHILD -> child = true;
                default -> {
                    System.err.println("usage: NavfnComparison --navfn DRIVER [--rounds N] [--grids a,b] "
                            + "[--whole PLANNER] [--plan PLANNER] [--questions whole,plan,field] [--one-jvm]");
                    System.exit(2);
                }
            }
        }
        if (navfn == null || rounds < 2 || questions.isEmpty() || !QUESTIONS.containsAll(questions)) {
            System.err.println("NavfnComparison: --navfn DRIVER is required, --rounds at least 2 and --questions "
                    + "among " + String.join(",", QUESTIONS));
            System.exit(2);
        }
        Results results = new Results();
        if (oneJvm || child) {
            measure(navfn, grids, questions, rounds, wholePlanner, planPlanner, results);
        } else {
            for (String grid : grids) {
                for (String question : questions) {
                    measureInChild(List.of("--navfn", navfn.toString(), "--rounds", Integer.toString(rounds),
                            "--grids", grid, "--questions", question, "--whole", wholePlanner, "--plan", planPlanner),
                            results);
                }
            }
        }
        if (child) {
            results.write(System.out);
            return;
        }
        System.out.println(oneJvm
                ? "All grids and questions in this one JVM (--one-jvm)."
                : "Each grid and question in a JVM of its own, as a robot runs one planner on its map.");
        System.out.println();
        printTimes("wall-clock time", grids, questions, results.wall, rounds, wholePlanner, planPlanner);
        printTimes("CPU time of the calling thread", grids, questions, results.cpu, rounds, wholePlanner, planPlanner);
        printOutcomes(grids, questions, results.outcomes);
    }

    /**
     * Runs this class for one grid and question in a new JVM (same java, class path and JVM options), which reports
     * its samples and outcomes to {@code results}.
     */
    private static void measureInChild(List<String> arguments, Results results)
            throws IOException, InterruptedException {
        List<String> command = new ArrayList<>();
        command.add(ProcessHandle.current().info().command().orElse("java"));
        command.addAll(ManagementFactory.getRuntimeMXBean().getInputArguments());
        command.add("-cp");
        command.add(System.getProperty("java.class.path"));
        command.add(NavfnComparison.class.getName());
        command.addAll(arguments);
        command.add(CHILD);
        Process process = new ProcessBuilder(command).redirectError(ProcessBuilder.Redirect.INHERIT).start();
        try (BufferedReader in = new BufferedReader(
                new InputStreamReader(process.getInputStream(), StandardCharsets.UTF_8))) {
            results.read(in);
        } catch (IOException e) {
            process.destroyForcibly(); // an unreadable report: the measuring JVM (and its navfn driver) end with it
            throw e;
        }
        int status = process.waitFor();
        if (status != 0) {
            throw new IOException("the measurement of " + arguments + " ended with status " + status);
        }
    }

    /** Times both planners on the grids and questions, in this JVM, alternating; adds to {@code results}. */
    private static void measure(Path navfn, List<String> grids, List<String> questions, int rounds,
            String wholePlanner, String planPlanner, Results results) throws IOException, InterruptedException {
        Map<String, Sample> samples = results.wall;
        Map<String, Sample> cpuSamples = results.cpu;
        Map<String, Outcome> outcomes = results.outcomes;
        Path folder = Files.createTempDirectory("sabot-navfn-grids");
        Process process = new ProcessBuilder(navfn.toString()).redirectError(ProcessBuilder.Redirect.INHERIT).start();
        try (PrintWriter toNavfn = new PrintWriter(process.getOutputStream(), true, StandardCharsets.US_ASCII);
                BufferedReader fromNavfn = new BufferedReader(
                        new InputStreamReader(process.getInputStream(), StandardCharsets.US_ASCII))) {
            // one pair of planners per grid, as the driver makes a NavFn per grid: a robot's planner keeps its map,
            // and one planner shared by grids of different sizes would reallocate its arrays at every switch
            Map<String, Planner> planners = new LinkedHashMap<>();
            Map<String, Field> fields = new LinkedHashMap<>();
            Map<String, BenchmarkGrids.Scenario> scenarios = new LinkedHashMap<>();
            for (String name : grids) {
                BenchmarkGrids.Scenario scenario = BenchmarkGrids.scenario(name);
                scenarios.put(name, scenario);
                Files.deleteIfExists(folder.resolve(name + ".pgm"));
            }
            for (int round = 0; round < rounds + 1; round++) {
                for (String name : grids) {
                    BenchmarkGrids.Scenario scenario = scenarios.get(name);
                    GridGeometry g = scenario.costmap().geometry();
                    Path pgm = folder.resolve(name + ".pgm");
                    if (!Files.exists(pgm)) {
                        MapServerFormat.saveCostmapImage(scenario.costmap(), pgm);
                    }
                    send(toNavfn, fromNavfn, "load " + pgm, "ok");
                    int calls = g.cellCount() <= 20_000 ? 201 : g.cellCount() <= 1_000_000 ? 11 : 5;
                    Cell s = g.cellAt(scenario.start()).orElseThrow();
                    Cell t = g.cellAt(scenario.goal()).orElseThrow();
                    String cells = s.column() + " " + (g.height() - 1 - s.row()) + " " + t.column() + " "
                            + (g.height() - 1 - t.row());
                    for (String question : questions) {
                        String plannerName = question.equals("plan") ? planPlanner : wholePlanner;
                        Planner sabot = question.equals("field") ? null : planners.computeIfAbsent(name + "/"
                                + question, k -> Planners.byName(plannerName, CostModel.standard()).orElseThrow());
                        Field field = question.equals("field") ? fields.computeIfAbsent(name, k -> new Field(scenario))
                                : null;
                        String navfnMode = switch (question) {
                            case "whole" -> "whole";
                            case "plan" -> "makeplan";
                            default -> "field";
                        };
                        boolean navfnFirst = round % 2 == 1;
                        for (int side = 0; side < 2; side++) {
                            boolean runNavfn = (side == 0) == navfnFirst;
                            String key = name + "/" + question + "/" + (runNavfn ? "navfn" : "sabot");
                            double[] times;
                            double[] cpu;
                            if (runNavfn) {
                                String answer = send(toNavfn, fromNavfn,
                                        "time " + navfnMode + " " + cells + " " + calls, "times");
                                times = numbers(answer, "times");
                                cpu = numbers(receive(fromNavfn, "cpu"), "cpu");
                                String result = receive(fromNavfn, "result");
                                outcomes.putIfAbsent(key, navfnOutcome(scenario, result));
                            } else {
                                times = new double[calls];
                                cpu = new double[calls];
                                PlanResult last = null;
                                for (int i = 0; i < calls; i++) {
                                    long cpuBegin = THREAD.getCurrentThreadCpuTime();
                                    long begin = System.nanoTime();
                                    if (field != null) {
                                        field.compute();
                                    } else {
                                        last = sabot.plan(scenario.costmap(), scenario.start(), scenario.goal());
                                    }
                                    times[i] = (System.nanoTime() - begin) / 1e6;
                                    cpu[i] = (THREAD.getCurrentThreadCpuTime() - cpuBegin) / 1e6;
                                }
                                outcomes.putIfAbsent(key, field != null
                                        ? new Outcome(field.reached(), Double.NaN, Double.NaN)
                                        : sabotOutcome(last));
                            }
                            if (round > 0) {
                                samples.computeIfAbsent(key, k -> new Sample()).add(times);
                                cpuSamples.computeIfAbsent(key, k -> new Sample()).add(cpu);
                            }
                        }
                    }
                }
            }
            planners.values().forEach(Planner::close);
            toNavfn.println("quit");
        } finally {
            process.waitFor();
            for (String name : grids) {
                Files.deleteIfExists(folder.resolve(name + ".pgm"));
            }
            Files.deleteIfExists(folder);
        }
    }

    private static void printTimes(String what, List<String> grids, List<String> questions,
            Map<String, Sample> samples, int rounds, String wholePlanner, String planPlanner) {
        System.out.printf(Locale.ROOT, "%s, %d rounds after one warm-up round; per cell: best round's median / median "
                + "of all calls, ms; ratio Sabot / navfn of each%n%n", what, rounds);
        StringBuilder header = new StringBuilder("| grid |");
        StringBuilder rule = new StringBuilder("|---|");
        for (String question : questions) {
            header.append(switch (question) {
                case "whole" -> " navfn whole grid (`calcNavFnDijkstra(false)`) | Sabot `" + wholePlanner
                        + "`, 1 thread | ratio |";
                case "plan" -> " navfn `makePlan` (`calcNavFnDijkstra(true)`) | Sabot `" + planPlanner + "` | ratio |";
                default -> " navfn navigation function alone (`propNavFnDijkstra`) | Sabot navigation function alone "
                        + "(`compute`) | ratio |";
            });
            rule.append("---|---|---|");
        }
        System.out.println(header);
        System.out.println(rule);
        for (String name : grids) {
            StringBuilder row = new StringBuilder("| " + name + " |");
            for (String question : questions) {
                Sample n = samples.get(name + "/" + question + "/navfn");
                Sample s = samples.get(name + "/" + question + "/sabot");
                row.append(String.format(Locale.ROOT, " %s / %s | %s / %s | **%.2f** / %.2f |", ms(n.best()),
                        ms(n.median()), ms(s.best()), ms(s.median()), s.best() / n.best(), s.median() / n.median()));
            }
            System.out.println(row);
        }
        System.out.println();
    }

    private static void printOutcomes(List<String> grids, List<String> questions, Map<String, Outcome> outcomes) {
        System.out.println("| grid | question | navfn reached cells | navfn path cost | Sabot reached cells | Sabot path cost "
                + "| cost ratio Sabot / navfn |");
        System.out.println("|---|---|---|---|---|---|---|");
        for (String name : grids) {
            for (String question : questions) {
                Outcome n = outcomes.get(name + "/" + question + "/navfn");
                Outcome s = outcomes.get(name + "/" + question + "/sabot");
                String ratio = question.equals("field") ? "—"
                        : String.format(Locale.ROOT, "%.4f", s.pathCost() / n.pathCost());
                System.out.printf(Locale.ROOT, "| %s | %s | %d | %s | %d | %s | %s |%n", name, question,
                        n.reached(), cost(n.pathCost()), s.reached(), cost(s.pathCost()), ratio);
            }
        }
    }

    /** A path's cost to one decimal, or a dash where the question has no path. */
    private static String cost(double value) {
        return Double.isNaN(value) ? "—" : String.format(Locale.ROOT, "%.1f", value);
    }

    private static String ms(double value) {
        return String.format(Locale.ROOT, value < 1 ? "%.3f" : value < 100 ? "%.1f" : "%.0f", value);
    }

    private static Outcome sabotOutcome(PlanResult result) {
        if (result instanceof PlanResult.Found found) {
            return new Outcome(found.field().reachedCells(), found.path().cost(), found.path().length());
        }
        return new Outcome(0, Double.NaN, Double.NaN);
    }

    /** navfn's path (image cells, integers at cell centres) measured with Sabot's cost integral. */
    private static Outcome navfnOutcome(BenchmarkGrids.Scenario scenario, String result) {
        String[] fields = result.trim().split(" ");
        long reached = Long.parseLong(fields[1]);
        int length = Integer.parseInt(fields[2]);
        if (length == 0) {
            return new Outcome(reached, Double.NaN, Double.NaN);
        }
        GridGeometry g = scenario.costmap().geometry();
        List<Point2D> path = new ArrayList<>(length);
        for (int i = 0; i < length; i++) {
            double x = Double.parseDouble(fields[3 + 2 * i]);
            double y = Double.parseDouble(fields[4 + 2 * i]);
            path.add(g.toMap(x + 0.5, g.height() - 0.5 - y));
        }
        return new Outcome(reached, CostModel.standard().pathCost(scenario.costmap(), path), CostModel.length(path));
    }

    private static double[] numbers(String line, String verb) {
        return Arrays.stream(line.substring(verb.length()).trim().split(" ")).mapToDouble(Double::parseDouble).toArray();
    }

    private static String send(PrintWriter out, BufferedReader in, String command, String expected)
            throws IOException {
        out.println(command);
        return receive(in, expected);
    }

    private static String receive(BufferedReader in, String expected) throws IOException {
        String line = in.readLine();
        if (line == null || !line.startsWith(expected)) {
            throw new IOException("navfn driver answered '" + line + "', expected '" + expected + " ...'");
        }
        return line;
    }

    static double median(double[] sorted) {
        int n = sorted.length;
        return n % 2 == 1 ? sorted[n / 2] : (sorted[n / 2 - 1] + sorted[n / 2]) / 2;
    }
}
