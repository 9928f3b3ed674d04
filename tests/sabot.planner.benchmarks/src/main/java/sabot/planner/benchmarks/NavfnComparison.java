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

/**
 * Times ROS navfn and Sabot's planners in one process, alternating, on the grids of {@link BenchmarkGrids}:
 * {@code ./sabot bench navfn --navigation CHECKOUT} (tools/bench-navfn builds navfn's driver; this class drives it over
 * its standard input). Two questions, each asked of both planners with the same start and goal:
 * <ul>
 * <li><b>whole</b>: the navigation function over the whole reachable grid and the path from the start (navfn
 * {@code calcNavFnDijkstra(false)} from the goal; Sabot {@code lpn}, one thread);</li>
 * <li><b>plan</b>: the robot's question, start to goal (navfn as {@code NavfnROS::makePlan} calls it:
 * {@code calcNavFnDijkstra(true)} propagating from the robot, stopped when the goal cell has a value; Sabot
 * {@code lpn-focused} by default).</li>
 * </ul>
 * Each round runs a batch of calls per grid and question, navfn then Sabot in odd rounds and the other way round in
 * even ones; the first round warms both up and is not counted. Reported: the best round's median per call (best of
 * rounds) and the median of all counted calls, of the wall-clock time and of the CPU time of the calling thread (on a
 * shared machine the wall clock also counts the time other processes held the core; both sides measure the same
 * calls the same way: {@code clock_gettime(CLOCK_THREAD_CPUTIME_ID)} in the driver, {@link ThreadMXBean} here); path
 * costs are Sabot's cost integral ({@link CostModel#pathCost}) of both paths.
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

    private static final ThreadMXBean THREAD = ManagementFactory.getThreadMXBean();

    private NavfnComparison() {
    }

    public static void main(String[] args) throws IOException, InterruptedException {
        Path navfn = null;
        int rounds = 5;
        List<String> grids = List.of("random-100", "random-1000", "random-2000", "maze-1000", "enclosed-1000");
        String wholePlanner = "lpn";
        String planPlanner = "lpn-focused";
        for (int i = 0; i < args.length; i++) {
            switch (args[i]) {
                case "--navfn" -> navfn = Path.of(args[++i]);
                case "--rounds" -> rounds = Integer.parseInt(args[++i]);
                case "--grids" -> grids = List.of(args[++i].split(","));
                case "--whole" -> wholePlanner = args[++i];
                case "--plan" -> planPlanner = args[++i];
                default -> {
                    System.err.println("usage: NavfnComparison --navfn DRIVER [--rounds N] [--grids a,b] "
                            + "[--whole PLANNER] [--plan PLANNER]");
                    System.exit(2);
                }
            }
        }
        if (navfn == null || rounds < 2) {
            System.err.println("NavfnComparison: --navfn DRIVER is required and --rounds at least 2");
            System.exit(2);
        }
        Path folder = Files.createTempDirectory("sabot-navfn-grids");
        Process process = new ProcessBuilder(navfn.toString()).redirectError(ProcessBuilder.Redirect.INHERIT).start();
        try (PrintWriter toNavfn = new PrintWriter(process.getOutputStream(), true, StandardCharsets.US_ASCII);
                BufferedReader fromNavfn = new BufferedReader(
                        new InputStreamReader(process.getInputStream(), StandardCharsets.US_ASCII))) {
            // one pair of planners per grid, as the driver makes a NavFn per grid: a robot's planner keeps its map,
            // and one planner shared by grids of different sizes would reallocate its arrays at every switch
            Map<String, Planner> planners = new LinkedHashMap<>();
            Map<String, Sample> samples = new LinkedHashMap<>();
            Map<String, Sample> cpuSamples = new LinkedHashMap<>();
            Map<String, Outcome> outcomes = new LinkedHashMap<>();
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
                    for (String question : List.of("whole", "plan")) {
                        String plannerName = question.equals("whole") ? wholePlanner : planPlanner;
                        Planner sabot = planners.computeIfAbsent(name + "/" + question,
                                k -> Planners.byName(plannerName, CostModel.standard()).orElseThrow());
                        String navfnMode = question.equals("whole") ? "whole" : "makeplan";
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
                                    last = sabot.plan(scenario.costmap(), scenario.start(), scenario.goal());
                                    times[i] = (System.nanoTime() - begin) / 1e6;
                                    cpu[i] = (THREAD.getCurrentThreadCpuTime() - cpuBegin) / 1e6;
                                }
                                outcomes.putIfAbsent(key, sabotOutcome(last));
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
            printTimes("wall-clock time", grids, samples, rounds, wholePlanner, planPlanner);
            printTimes("CPU time of the calling thread", grids, cpuSamples, rounds, wholePlanner, planPlanner);
            printOutcomes(grids, outcomes);
        } finally {
            process.waitFor();
            for (String name : grids) {
                Files.deleteIfExists(folder.resolve(name + ".pgm"));
            }
            Files.deleteIfExists(folder);
        }
    }

    private static void printTimes(String what, List<String> grids, Map<String, Sample> samples, int rounds,
            String wholePlanner, String planPlanner) {
        System.out.printf(Locale.ROOT, "%s, %d rounds after one warm-up round; per cell: best round's median / median "
                + "of all calls, ms; ratio Sabot / navfn of each%n%n", what, rounds);
        System.out.println("| grid | navfn whole grid (`calcNavFnDijkstra(false)`) | Sabot `" + wholePlanner
                + "`, 1 thread | ratio | navfn `makePlan` (`calcNavFnDijkstra(true)`) | Sabot `" + planPlanner
                + "` | ratio |");
        System.out.println("|---|---|---|---|---|---|---|");
        for (String name : grids) {
            StringBuilder row = new StringBuilder("| " + name + " |");
            for (String question : List.of("whole", "plan")) {
                Sample n = samples.get(name + "/" + question + "/navfn");
                Sample s = samples.get(name + "/" + question + "/sabot");
                row.append(String.format(Locale.ROOT, " %s / %s | %s / %s | **%.2f** / %.2f |", ms(n.best()),
                        ms(n.median()), ms(s.best()), ms(s.median()), s.best() / n.best(), s.median() / n.median()));
            }
            System.out.println(row);
        }
        System.out.println();
    }

    private static void printOutcomes(List<String> grids, Map<String, Outcome> outcomes) {
        System.out.println("| grid | question | navfn reached cells | navfn path cost | Sabot reached cells | Sabot path cost "
                + "| cost ratio Sabot / navfn |");
        System.out.println("|---|---|---|---|---|---|---|");
        for (String name : grids) {
            for (String question : List.of("whole", "plan")) {
                Outcome n = outcomes.get(name + "/" + question + "/navfn");
                Outcome s = outcomes.get(name + "/" + question + "/sabot");
                System.out.printf(Locale.ROOT, "| %s | %s | %d | %.1f | %d | %.1f | %.4f |%n", name, question,
                        n.reached(), n.pathCost(), s.reached(), s.pathCost(), s.pathCost() / n.pathCost());
            }
        }
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
