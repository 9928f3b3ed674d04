package sabot.products;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.awt.image.BufferedImage;
import java.io.IOException;
import java.net.ServerSocket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.TimeUnit;

import javax.imageio.ImageIO;

import org.junit.jupiter.api.Test;

import sabot.testsupport.process.ProcessConsole;

/**
 * {@code ./sabot demo --headless} as a user runs it: the private server, the simulated robot driven by the onboard
 * product and the workbench on a virtual display; the demo sends its default goal behind the lab's partition. Judged
 * on the simulator's ground truth (target/demo/truth.csv) and on the screenshot the demo takes
 * (target/demo/workbench.png): the lab map's walls and the robot are on it.
 */
class DemoTest {

    /** The demo's default goal (DEMO_DEFAULT_GOAL in ./sabot), behind the partition from the robot's start. */
    private static final double GOAL_X = 1.5;
    private static final double GOAL_Y = 4.0;
    /** How far the true pose may be from the goal: the goal's own tolerance (0.1 m) plus the localisation error. */
    private static final double TOLERANCE_M = 0.15;
    /** The demo's time limit: well above its figure (goal reached 22 s after it was sent); the test stops it then. */
    private static final int DEMO_LIMIT_S = 120;
    /** How long the demo may take to start its workbench, a build of the products included (./sabot's own). */
    private static final int BUILD_LIMIT_S = 900;
    /** The lab map's walls as the workspace paints them (an occupied cell of the map, grey 25). */
    private static final int WALL_RGB = 0x191919;
    /**
     * A live, unselected robot's footprint as the workspace fills it: its body colour (30, 110, 200) at alpha 160 over
     * white, painted opaque.
     */
    private static final int ROBOT_FILL_RGB = 0x71a4dc;
    /** Fewer wall pixels than this: no map (the lab's walls paint some 12,000 at the demo's zoom). */
    private static final int MIN_WALL_PIXELS = 5000;
    /** Fewer footprint pixels than this: no robot (its 0.25 m footprint fills some 150). */
    private static final int MIN_ROBOT_PIXELS = 50;

    /** The views of the plug-ins the demo's workbench comes with (docs/WORKBENCH-PLUGINS.md). */
    private static final List<String> PLUGIN_VIEWS = List.of("Joystick", "PID Tuning", "Remote Files", "Identity",
            "Traffic");

    @Test
    void theDemoRobotReachesItsGoalAndTheScreenshotShowsTheMapAndTheRobot() throws Exception {
        Path root = ProductProcess.root();
        Path demo = root.resolve("target/demo");
        ProcessBuilder pb = new ProcessBuilder(root.resolve("sabot").toString(), "demo", "--headless", "--for",
                Integer.toString(DEMO_LIMIT_S)).directory(root.toFile()).redirectErrorStream(true);
        // a port of its own: a demo a user runs on the default port, or another test's server, must not be met
        pb.environment().put("SABOT_XMPP_PORT", Integer.toString(freePort()));
        pb.environment().put("SABOT_JAVA_HOME", System.getProperty("java.home"));
        Process process = pb.start();
        ProcessConsole console = ProcessConsole.ofPipe("./sabot demo", process, l -> System.out.println("  | " + l));
        try {
            // the demo first builds what is older than its sources (nothing, after the reactor's own build)
            console.await(l -> l.contains("workbench started"), "saying the workbench started", BUILD_LIMIT_S);
            // the demo's workbench comes with the plug-ins installed from the update site (DEMO_PLUGINS in ./sabot)
            String window = ProcessConsole.tail("the demo's workbench", process, demo.resolve("workbench.log"))
                    .await(l -> l.contains("Sabot Workbench window open"), "saying its window is open", 120);
            for (String view : PLUGIN_VIEWS) {
                assertTrue(window.matches(".*views: .*\\b" + view + "\\b.*"), "no " + view + " view: " + window);
            }
            // the demo's status line of robot 1 each second, until its mission has ended one way or the other
            String ended = console.await(l -> l.matches(".*\\d+s sabot-01: .*mission (done|failed|aborted).*"),
                    "with sabot-01's mission ended", DEMO_LIMIT_S + 60);
            assertTrue(ended.contains("(goal reached)"), "the demo robot's mission did not reach the goal: " + ended);
            // SIGTERM, as Ctrl-C: the demo stops everything it started and exits 0
            process.toHandle().destroy();
            assertTrue(process.waitFor(60, TimeUnit.SECONDS), "the demo did not stop within 60 s:\n" + console
                    .output());
            console.drain(TimeUnit.SECONDS.toMillis(10));
            assertEquals(0, process.exitValue(), console.output());
            console.await(l -> l.contains("demo stopped"), "saying the demo stopped", 1);
        } finally {
            process.descendants().forEach(ProcessHandle::destroyForcibly);
            process.destroyForcibly();
        }

        double[] truth = lastTruth(demo.resolve("truth.csv"));
        double off = Math.hypot(truth[0] - GOAL_X, truth[1] - GOAL_Y);
        System.out.printf(Locale.ROOT, "[demo] robot 1 stopped at (%.3f, %.3f), %.3f m from the goal (%.1f, %.1f)%n",
                truth[0], truth[1], off, GOAL_X, GOAL_Y);
        assertTrue(off <= TOLERANCE_M, String.format(Locale.ROOT, "robot 1 is %.3f m from the goal", off));

        BufferedImage png = ImageIO.read(demo.resolve("workbench.png").toFile());
        int walls = count(png, WALL_RGB);
        int robot = count(png, ROBOT_FILL_RGB);
        System.out.printf("[demo] screenshot %dx%d: %d wall pixels, %d robot pixels%n", png.getWidth(), png
                .getHeight(), walls, robot);
        assertTrue(walls >= MIN_WALL_PIXELS, "the screenshot shows no map: " + walls + " wall pixels");
        assertTrue(robot >= MIN_ROBOT_PIXELS, "the screenshot shows no robot: " + robot + " footprint pixels");
    }

    /** @return robot 1's last true x and y in sabot-sim's truth CSV (t_s, robot, x_m, y_m, ...) */
    private static double[] lastTruth(Path csv) throws IOException {
        List<String> rows = Files.readAllLines(csv);
        for (int i = rows.size() - 1; i > 0; i--) {
            String[] f = rows.get(i).split(",");
            if (f.length >= 4 && f[1].equals("1")) {
                return new double[] { Double.parseDouble(f[2]), Double.parseDouble(f[3]) };
            }
        }
        throw new AssertionError("no row of robot 1 in " + csv);
    }

    private static int count(BufferedImage image, int rgb) {
        int n = 0;
        for (int y = 0; y < image.getHeight(); y++) {
            for (int x = 0; x < image.getWidth(); x++) {
                if ((image.getRGB(x, y) & 0xffffff) == rgb) {
                    n++;
                }
            }
        }
        return n;
    }

    private static int freePort() throws IOException {
        try (ServerSocket s = new ServerSocket(0)) {
            return s.getLocalPort();
        }
    }
}
