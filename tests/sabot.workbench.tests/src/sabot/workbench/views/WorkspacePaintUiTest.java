package sabot.workbench.views;

import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Instant;
import java.util.Arrays;
import java.util.Locale;

import org.eclipse.swt.graphics.GC;
import org.eclipse.swt.graphics.Image;
import org.eclipse.swt.graphics.ImageData;
import org.eclipse.swt.graphics.RGB;
import org.eclipse.swt.widgets.Canvas;
import org.eclipse.swt.widgets.Display;
import org.eclipse.ui.PlatformUI;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

import sabot.workbench.fleet.RobotState;
import sabot.workbench.map.MapViewport;

/**
 * The Workspace's paint of a hundred robots on a mission (trail of 600 points, path, goal, obstacles, ellipse),
 * frame by frame in the real workbench under Xvfb, without a server or other load: the paint's UI-thread CPU time, its
 * wall time, and the frame's wall time up to the X server's answer to a round trip after it (what the display still
 * had to draw), and the X server's own CPU time a frame (Xvfb rasterizes what cairo's XRender requests ask). Prints
 * the figures; asserts that each robot is drawn where it is.
 */
class WorkspacePaintUiTest {

    static final int ROBOTS = 100;
    /** Frames measured: enough for a p99 that is not the maximum. */
    static final int FRAMES = 200;
    /** Clock ticks a second of /proc/PID/stat's utime and stime (USER_HZ, 100 on Linux). */
    static final double CLOCK_TICKS_PER_S = 100;

    private DrivenFleet fleet;

    @AfterEach
    void closeFleet() {
        if (fleet != null) {
            fleet.close();
            FleetViewUpdatesUiTest.drain();
        }
    }

    @Test
    void aHundredRobotsOnAMissionArePaintedAndTheFrameIsMeasured() {
        WorkspaceView workspace = workspace();
        fleet = new DrivenFleet();
        Instant at = Instant.now();
        for (int i = 0; i < ROBOTS; i++) {
            fleet.put(DrivenFleet.busy(i, FleetViewUpdatesUiTest.x(i), FleetViewUpdatesUiTest.y(i), 0, at));
        }
        FleetViewUpdatesUiTest.waitFor(() -> workspace.map() != null, 10, () -> "no map: " + workspace.lastMessage());
        workspace.home();
        Canvas canvas = workspace.canvas();
        measure(workspace);

        // what is drawn: the footprint's fill (blue) half a radius behind each of a few robots' centres
        MapViewport v = workspace.viewport();
        ImageData data = screen(canvas);
        // the frame as the eye sees it, to judge the look (not under docs/images: a test fixture, not a view with a
        // live robot)
        save(data, "target/workspace-100-robots.png");
        for (int i : new int[] { 0, 37, 99 }) {
            RobotState r = fleet.get(DrivenFleet.jid(i));
            double behind = 0.5 * WorkspaceView.FOOTPRINT_RADIUS_M;
            int px = (int) Math.round(v.toScreenX(r.pose().pose().x() - behind * Math.cos(r.pose().pose().theta())));
            int py = (int) Math.round(v.toScreenY(r.pose().pose().y() - behind * Math.sin(r.pose().pose().theta())));
            RGB at2 = data.palette.getRGB(data.getPixel(px, py));
            assertTrue(at2.blue > at2.red + 40, "robot " + i + " not drawn at " + px + "," + py + ": " + at2);
        }
    }

    /**
     * The static layers are kept from frame to frame (WorkspaceView.drawBackground): they must follow the view. The
     * x axis (dark red, from the origin 60 px to the right) is looked for on the screen: after a pan it has moved by
     * the pan, after a zoom it starts where the viewport puts the origin.
     */
    @Test
    void theKeptStaticLayersFollowThePanAndTheZoom() {
        WorkspaceView workspace = workspace();
        workspace.home();
        MapViewport v = workspace.viewport();
        int[] before = repaintAndFindXAxis(workspace);
        v.panByPixels(37, -23);
        int[] panned = repaintAndFindXAxis(workspace);
        assertTrue(panned[0] == before[0] + 37 && Math.abs(panned[1] - (before[1] - 23)) <= 1, "after the pan the "
                + "x axis is at " + panned[0] + "," + panned[1] + ", not 37,-23 from " + before[0] + "," + before[1]);
        // twice the scale about a point 100 px right of the origin: the origin moves 100 px left, the axis keeps its
        // 60 px
        v.zoomAt(2, panned[0] + 100, panned[1]);
        int[] zoomed = repaintAndFindXAxis(workspace);
        int ox = (int) Math.round(v.toScreenX(0));
        int oy = (int) Math.round(v.toScreenY(0));
        assertTrue(Math.abs(zoomed[0] - ox) <= 1 && Math.abs(zoomed[1] - oy) <= 1, "after the zoom the x axis "
                + "starts at " + zoomed[0] + "," + zoomed[1] + ", the viewport's origin is at " + ox + "," + oy);
        workspace.home();
    }

    /**
     * Repaints the Workspace, then finds the x axis on the screen: the leftmost pixel of the longest dark red
     * horizontal run.
     *
     * @return its column and row
     */
    private static int[] repaintAndFindXAxis(WorkspaceView workspace) {
        Canvas canvas = workspace.canvas();
        ImageData data;
        try (FrameStatistics frames = FrameStatistics.of(workspace)) {
            canvas.redraw();
            FleetViewUpdatesUiTest.waitFor(() -> frames.count() > 0, 5, () -> "no paint");
            data = screen(canvas);
        }
        RGB axis = canvas.getDisplay().getSystemColor(org.eclipse.swt.SWT.COLOR_DARK_RED).getRGB();
        int[] best = { -1, -1 };
        int bestLength = 0;
        for (int y = 0; y < data.height; y++) {
            int run = 0;
            for (int x = 0; x < data.width; x++) {
                run = data.palette.getRGB(data.getPixel(x, y)).equals(axis) ? run + 1 : 0;
                if (run > bestLength) {
                    bestLength = run;
                    best = new int[] { x - run + 1, y };
                }
            }
        }
        if (bestLength < 40) {
            save(data, "target/workspace-no-axis.png");
        }
        assertTrue(bestLength >= 40, "no x axis on the screen (longest dark red run " + bestLength + " px, "
                + data.width + "x" + data.height + "; the screen: target/workspace-no-axis.png)");
        return best;
    }

    static void save(ImageData data, String png) {
        org.eclipse.swt.graphics.ImageLoader loader = new org.eclipse.swt.graphics.ImageLoader();
        loader.data = new ImageData[] { data };
        loader.save(png, org.eclipse.swt.SWT.IMAGE_PNG);
    }

    /** @return what the canvas shows on the screen, read back from the X server */
    static ImageData screen(Canvas canvas) {
        Image shot = new Image(canvas.getDisplay(), canvas.getSize().x, canvas.getSize().y);
        try {
            GC gc = new GC(canvas);
            gc.copyArea(shot, 0, 0);
            gc.dispose();
            return shot.getImageData();
        } finally {
            shot.dispose();
        }
    }

    /** Paints {@link #FRAMES} frames after 10 of warm-up, the robots moved a little before each; prints the figures. */
    private void measure(WorkspaceView workspace) {
        Canvas canvas = workspace.canvas();
        Display d = canvas.getDisplay();
        Instant at;
        long[] cpu = new long[FRAMES];
        long[] wall = new long[FRAMES];
        long[] total = new long[FRAMES];
        // the X server's CPU over the measured frames: the display's own work on what the paints sent
        long xPid = xServerPid();
        long xTicks0 = 0;
        FrameStatistics frames = FrameStatistics.of(workspace);
        for (int f = -10; f < FRAMES; f++) { // 10 frames to warm up the JIT and the X server's caches
            at = Instant.now();
            for (int i = 0; i < ROBOTS; i++) {
                RobotState r = fleet.get(DrivenFleet.jid(i));
                fleet.put(r.withPose(DrivenFleet.pose(FleetViewUpdatesUiTest.x(i) + 0.002 * f, FleetViewUpdatesUiTest
                        .y(i), 0.01 * f, at), at, DrivenFleet.receipt(at)));
            }
            FleetViewUpdatesUiTest.drain();
            if (f == 0) {
                d.getCursorLocation(); // the warm-up's requests done before the X server's CPU is read
                xTicks0 = cpuTicks(xPid);
            }
            int frames0 = frames.count();
            canvas.redraw();
            FleetViewUpdatesUiTest.waitFor(() -> frames.count() > frames0, 5, () -> "no paint");
            d.getCursorLocation(); // a round trip: the X server answers once it has done what came before
            long t1 = System.nanoTime();
            if (f >= 0) {
                cpu[f] = frames.cpuNanos()[frames.cpuNanos().length - 1];
                wall[f] = frames.wallNanos()[frames.wallNanos().length - 1];
                total[f] = wall[f] + t1 - frames.lastEndNanos();
            }
        }
        frames.close();
        double xCpuMsPerFrame = (cpuTicks(xPid) - xTicks0) * 1000 / CLOCK_TICKS_PER_S / FRAMES;
        System.out.printf(Locale.ROOT, "[figure] Workspace paint, %d robots on a mission, %dx%d, no load, %d frames: "
                + "UI-thread CPU %s; X server (pid %d) CPU %.2f ms a frame (mean); paint wall %s; paint and the X "
                + "server's round trip after it %s%n", ROBOTS, canvas.getSize().x, canvas.getSize().y, FRAMES, stats(
                        cpu), xPid, xCpuMsPerFrame, stats(wall), stats(total));
    }

    private static String stats(long[] nanos) {
        long[] s = nanos.clone();
        Arrays.sort(s);
        return String.format(Locale.ROOT, "p50 %.2f ms, p90 %.2f ms, p99 %.2f ms, max %.2f ms", s[s.length / 2] / 1e6,
                s[(int) (s.length * 0.9)] / 1e6, s[(int) (s.length * 0.99)] / 1e6, s[s.length - 1] / 1e6);
    }

    /** @return the pid of the X server of $DISPLAY, from its lock file {@code /tmp/.X<n>-lock} (xvfb-run's Xvfb) */
    static long xServerPid() {
        String display = System.getenv("DISPLAY");
        assertNotNull(display, "no DISPLAY");
        java.util.regex.Matcher m = java.util.regex.Pattern.compile(":(\\d+)").matcher(display);
        assertTrue(m.find(), "DISPLAY " + display);
        try {
            return Long.parseLong(Files.readString(Path.of("/tmp/.X" + m.group(1) + "-lock")).trim());
        } catch (IOException e) {
            throw new UncheckedIOException("X server's lock file of " + display, e);
        }
    }

    /** @return a process's user and system CPU time so far, clock ticks ({@code /proc/PID/stat} fields 14 and 15) */
    static long cpuTicks(long pid) {
        try {
            String stat = Files.readString(Path.of("/proc/" + pid + "/stat"));
            // the command name (field 2) is in parentheses and may hold spaces: count fields after its ')'
            String[] f = stat.substring(stat.lastIndexOf(')') + 2).split(" ");
            return Long.parseLong(f[11]) + Long.parseLong(f[12]);
        } catch (IOException e) {
            throw new UncheckedIOException("CPU time of process " + pid, e);
        }
    }

    static WorkspaceView workspace() {
        WorkspaceView w = (WorkspaceView) PlatformUI.getWorkbench().getActiveWorkbenchWindow().getActivePage()
                .findView(WorkspaceView.ID);
        assertNotNull(w, "workspace view not open");
        return w;
    }
}
