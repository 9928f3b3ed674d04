package sabot.workbench.internal;

import java.nio.file.Path;
import java.nio.file.Paths;

/**
 * Command-line options of the workbench application (after Equinox has taken its own):
 * {@code -sabot.screenshot FILE} saves a PNG of the window once it is open; {@code -sabot.exit} closes the
 * workbench right after start-up (and after the screenshot), for smoke tests and headless demos;
 * {@code -sabot.screenshot.live} takes the screenshot once a live robot is drawn on its map (at most
 * {@link #LIVE_WAIT_S} seconds after the window opened).
 *
 * @param screenshot where to save the screenshot, or null
 * @param exitAfterStartup close once the window is open
 * @param waitForLiveRobot take the screenshot once a live robot is on the map
 */
public record LaunchOptions(Path screenshot, boolean exitAfterStartup, boolean waitForLiveRobot) {

    /** Longest wait for a live robot before the screenshot is taken anyway, seconds. */
    public static final int LIVE_WAIT_S = 120;

    public static LaunchOptions parse(String[] args) {
        Path screenshot = null;
        boolean exit = false;
        boolean live = false;
        for (int i = 0; i < args.length; i++) {
            if (args[i].equals("-sabot.screenshot") && i + 1 < args.length) {
                screenshot = Paths.get(args[++i]).toAbsolutePath();
            } else if (args[i].equals("-sabot.screenshot.live")) {
                live = true;
            } else if (args[i].equals("-sabot.exit")) {
                exit = true;
            }
        }
        return new LaunchOptions(screenshot, exit, live);
    }
}
