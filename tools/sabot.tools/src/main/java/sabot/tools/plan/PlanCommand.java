package sabot.tools.plan;

import java.io.IOException;
import java.io.PrintStream;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Locale;

import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.map.Costmap;
import sabot.model.map.GridGeometry;
import sabot.model.map.MapServerFormat;
import sabot.planner.CostModel;
import sabot.planner.PlanResult;
import sabot.planner.Planner;
import sabot.planner.Planners;
import sabot.planner.costmap.CostmapLayers;
import sabot.planner.costmap.InflationParameters;
import sabot.planner.costmap.MovingObstacleModel;
import sabot.tools.render.PlanImage;

/**
 * {@code sabot plan}: plans once or repeatedly on a map file and prints, as its last line, one JSON object with the
 * outcome and the timings. Bad input gives one error line on standard error and exit status 2.
 */
public final class PlanCommand {

    static final String USAGE = """
            usage: sabot plan (--map FILE.yaml | --costmap FILE.pgm) --start X,Y --goal X,Y [--goal X,Y ...]
                              [--cells] [--planner lpn|lpn-bounded|lpn-focused|lpn-incremental|reference|dijkstra] [--repeat N] [--png OUT.png]
                              [--threads 1|2] [--resolution M] [--inscribed-radius M] [--inflation-radius M]
                              [--cost-scaling F] [--allow-unknown]
              --map            ROS map_server YAML (+ PGM); obstacles are inflated for the robot
              --costmap        raw 8-bit costmap PGM (0 free, 1..252 cost, 253 inscribed, 254 lethal, 255 unknown)
              --cells          start/goal are column,row with row 0 at the top of the image (else metres, map frame)
              --threads        1 or 2 (default 1); both compute on the calling thread (2 is accepted so
                               that scripts written for a two-thread planner keep working)
              --resolution     metres per cell of a --costmap image (default 1)
              --inscribed-radius, --inflation-radius (metres), --cost-scaling (1/m): inflation of a --map
                               (defaults 0.15, 0.55, 10)
              --allow-unknown  unknown cells may be crossed at the highest graded cost
            prints one JSON object as its last line: status, reason, cells, median_ms, min_ms, path_length (m),
            path_cost (cost units), waypoints""";

    /** Bad command-line input; the message is the error line. */
    static final class UsageException extends Exception {
        private static final long serialVersionUID = 1L;

        UsageException(String message) {
            super(message);
        }
    }

    private PlanCommand() {
    }

    public static void main(String[] args) {
        System.exit(run(args, System.out, System.err));
    }

    /** @return the exit status: 0 planned (found or unreachable), 2 bad input */
    public static int run(String[] args, PrintStream out, PrintStream err) {
        try {
            Options options = Options.parse(args);
            if (options.help) {
                out.println(USAGE);
                return 0;
            }
            out.println(execute(options));
            return 0;
        } catch (UsageException e) {
            err.println("sabot plan: error: " + e.getMessage());
            return 2;
        } catch (IOException e) {
            err.println("sabot plan: error: " + e.getMessage());
            return 2;
        } catch (IllegalArgumentException e) {
            err.println("sabot plan: error: " + e.getMessage());
            return 2;
        }
    }

    private static String execute(Options o) throws IOException, UsageException {
        Costmap costmap;
        if (o.costmap != null) {
            costmap = MapServerFormat.loadCostmapImage(Path.of(o.costmap), o.resolution, Pose2D.ORIGIN);
        } else {
            MapServerFormat.LoadedMap map = MapServerFormat.load(Path.of(o.map));
            InflationParameters inflation = new InflationParameters(o.inscribedRadius,
                    Math.max(o.inscribedRadius, o.inflationRadius), o.costScaling,
                    InflationParameters.DEFAULT_LETHAL_THRESHOLD,
                    sabot.planner.costmap.UnknownCellPolicy.KEEP_UNKNOWN);
            costmap = CostmapLayers.fromOccupancy(map.grid(), inflation, MovingObstacleModel.defaults()).costmap();
        }
        GridGeometry geometry = costmap.geometry();
        Point2D start = o.point(o.start, geometry, "--start");
        List<Point2D> goals = new ArrayList<>();
        for (String goal : o.goals) {
            goals.add(o.point(goal, geometry, "--goal"));
        }
        CostModel costModel = o.allowUnknown ? CostModel.allowingUnknown() : CostModel.standard();
        double[] millis = new double[o.repeat];
        PlanResult result = null;
        String plannerName;
        try (Planner planner = Planners.byName(o.planner, costModel, o.threads).orElseThrow(() -> new UsageException(
                "unknown planner '" + o.planner + "', expected one of " + String.join(", ", Planners.NAMES)))) {
            plannerName = planner.name();
            for (int i = 0; i < o.repeat; i++) {
                long begin = System.nanoTime();
                result = planner.plan(costmap, start, goals);
                millis[i] = (System.nanoTime() - begin) / 1e6;
            }
        }
        Arrays.sort(millis);
        double median = o.repeat % 2 == 1 ? millis[o.repeat / 2] : (millis[o.repeat / 2 - 1] + millis[o.repeat / 2]) / 2;
        if (o.png != null) {
            PlanImage image = PlanImage.of(costmap).scale(Math.max(1, Math.min(8, 800 / Math.max(geometry.width(),
                    geometry.height()))));
            if (result instanceof PlanResult.Found found) {
                image.withField(found.field()).withPath(found.path().waypoints());
            }
            image.writePng(Path.of(o.png));
        }
        StringBuilder json = new StringBuilder("{");
        json.append("\"planner\":\"").append(plannerName).append('"');
        json.append(",\"threads\":").append(o.threads);
        switch (result) {
            case PlanResult.Found found -> json.append(",\"status\":\"ok\",\"reason\":null,\"detail\":null");
            case PlanResult.Unreachable u -> json.append(",\"status\":\"unreachable\",\"reason\":\"")
                    .append(u.reason().name().toLowerCase(Locale.ROOT)).append("\",\"detail\":\"")
                    .append(escape(u.detail())).append('"');
        }
        json.append(",\"cells\":").append(geometry.cellCount());
        json.append(",\"repeat\":").append(o.repeat);
        json.append(",\"median_ms\":").append(format(median));
        json.append(",\"min_ms\":").append(format(millis[0]));
        if (result instanceof PlanResult.Found found) {
            json.append(",\"reached_cells\":").append(found.field().reachedCells());
            json.append(",\"path_length\":").append(format(found.path().length()));
            json.append(",\"path_cost\":").append(format(found.path().cost()));
            json.append(",\"waypoints\":").append(found.path().waypoints().size());
        } else {
            json.append(",\"reached_cells\":null,\"path_length\":null,\"path_cost\":null,\"waypoints\":0");
        }
        return json.append('}').toString();
    }

    private static String format(double value) {
        return String.format(Locale.ROOT, "%.4f", value);
    }

    private static String escape(String text) {
        return text.replace("\\", "\\\\").replace("\"", "\\\"");
    }

    /** The parsed command line. */
    static final class Options {
        String map;
        String costmap;
        String start;
        final List<String> goals = new ArrayList<>();
        boolean cells;
        String planner = "lpn";
        int repeat = 1;
        int threads = 1;
        String png;
        double resolution = 1.0;
        double inscribedRadius = 0.15;
        double inflationRadius = InflationParameters.DEFAULT_INFLATION_RADIUS;
        double costScaling = InflationParameters.DEFAULT_COST_SCALING_FACTOR;
        boolean allowUnknown;
        boolean help;

        static Options parse(String[] args) throws UsageException {
            Options o = new Options();
            for (int i = 0; i < args.length; i++) {
                String arg = args[i];
                switch (arg) {
                    case "--map" -> o.map = value(args, ++i, arg);
                    case "--costmap" -> o.costmap = value(args, ++i, arg);
                    case "--start" -> o.start = value(args, ++i, arg);
                    case "--goal" -> o.goals.add(value(args, ++i, arg));
                    case "--cells" -> o.cells = true;
                    case "--planner" -> o.planner = value(args, ++i, arg);
                    case "--repeat" -> o.repeat = positiveInt(value(args, ++i, arg), arg);
                    case "--threads" -> o.threads = threads(value(args, ++i, arg), arg);
                    case "--png" -> o.png = value(args, ++i, arg);
                    case "--resolution" -> o.resolution = positive(value(args, ++i, arg), arg);
                    case "--inscribed-radius" -> o.inscribedRadius = nonNegative(value(args, ++i, arg), arg);
                    case "--inflation-radius" -> o.inflationRadius = nonNegative(value(args, ++i, arg), arg);
                    case "--cost-scaling" -> o.costScaling = positive(value(args, ++i, arg), arg);
                    case "--allow-unknown" -> o.allowUnknown = true;
                    case "--help", "-h" -> o.help = true;
                    default -> throw new UsageException("unknown argument '" + arg + "' (see --help)");
                }
            }
            if (o.help) {
                return o;
            }
            if ((o.map == null) == (o.costmap == null)) {
                throw new UsageException("give exactly one of --map FILE.yaml or --costmap FILE.pgm");
            }
            if (o.start == null) {
                throw new UsageException("missing --start X,Y");
            }
            if (o.goals.isEmpty()) {
                throw new UsageException("missing --goal X,Y");
            }
            return o;
        }

        Point2D point(String text, GridGeometry geometry, String option) throws UsageException {
            String[] parts = text.split(",");
            if (parts.length != 2) {
                throw new UsageException(option + " '" + text + "' is not X,Y");
            }
            double x = number(parts[0].strip(), option);
            double y = number(parts[1].strip(), option);
            if (!cells) {
                return new Point2D(x, y);
            }
            if (x != Math.rint(x) || y != Math.rint(y)) {
                throw new UsageException(option + " '" + text + "' must be integer column,row with --cells");
            }
            int column = (int) x;
            int imageRow = (int) y;
            if (!geometry.contains(column, geometry.height() - 1 - imageRow)) {
                throw new UsageException(option + " cell " + column + "," + imageRow + " is outside the "
                        + geometry.width() + " x " + geometry.height() + " map");
            }
            return geometry.cellCentre(column, geometry.height() - 1 - imageRow);
        }

        private static int threads(String text, String option) throws UsageException {
            int n = positiveInt(text, option);
            if (n > 2) {
                throw new UsageException(option + " must be 1 or 2, not " + text);
            }
            return n;
        }

        private static String value(String[] args, int index, String option) throws UsageException {
            if (index >= args.length || args[index].startsWith("--")) {
                throw new UsageException(option + " needs a value");
            }
            return args[index];
        }

        private static double number(String text, String option) throws UsageException {
            try {
                double v = Double.parseDouble(text);
                if (Double.isFinite(v)) {
                    return v;
                }
            } catch (NumberFormatException e) {
                // reported below
            }
            throw new UsageException(option + " value '" + text + "' is not a finite number");
        }

        private static double positive(String text, String option) throws UsageException {
            double v = number(text, option);
            if (v <= 0) {
                throw new UsageException(option + " must be positive, got " + text);
            }
            return v;
        }

        private static double nonNegative(String text, String option) throws UsageException {
            double v = number(text, option);
            if (v < 0) {
                throw new UsageException(option + " must not be negative, got " + text);
            }
            return v;
        }

        private static int positiveInt(String text, String option) throws UsageException {
            try {
                int v = Integer.parseInt(text);
                if (v >= 1) {
                    return v;
                }
            } catch (NumberFormatException e) {
                // reported below
            }
            throw new UsageException(option + " must be a positive integer, got '" + text + "'");
        }
    }
}
