package sabot.workbench.internal;

import java.nio.file.Path;
import java.nio.file.Paths;

/**
 * Command-line options of the workbench application (after Equinox has taken its own):
 * {@code -sabot.screenshot FILE} saves a PNG of the window once it is open; {@code -sabot.exit} closes the
 * workbench right after start-up (and after the screenshot), for smoke tests and headless demos;
 * {@code -sabot.screenshot.live} takes the screenshot once a live robot is drawn on its map,
 * {@code -sabot.screenshot.mission} once a robot's running mission is drawn (its planned path and a trail of at
 * least 20 cm); either waits at most {@link #LIVE_WAIT_S} seconds after the window opened.
 *
 * @param screenshot       where to save the screenshot, or null
 * @param exitAfterStartup close once the window is open
 * @param waitFor          what the screenshot waits for on the map; never null
 */
public record LaunchOptions(Path screenshot, boolean exitAfterStartup, Wait waitFor) {

    /** Longest wait for a live robot before the screenshot is taken anyway, seconds. */
    public static final int LIVE_WAIT_S = 120;

    /** What the screenshot waits for on the Workspace view's map. */
    public enum Wait {
        /** nothing: the first drawn window */
        NONE,
        /** a live robot (pose, fresh telemetry) drawn on the map */
        LIVE,
        /** a robot running a mission, its planned path and trail drawn */
        MISSION
    }

    public static LaunchOptions parse(String[] args) {
        Path screenshot = null;
        boolean exit = false;
        Wait wait = Wait.NONE;
        for (int i = 0; i < args.length; i++) {
            if (args[i].equals("-sabot.screenshot") && i + 1 < args.length) {
                screenshot = Paths.get(args[++i]).toAbsolutePath();
            } else if (args[i].equals("-sabot.screenshot.live")) {
                wait = wait == Wait.MISSION ? wait : Wait.LIVE;
            } else if (args[i].equals("-sabot.screenshot.mission")) {
                wait = Wait.MISSION;
            } else if (args[i].equals("-sabot.exit")) {
                exit = true;
            }
        }
        return new LaunchOptions(screenshot, exit, wait);
    }
}
