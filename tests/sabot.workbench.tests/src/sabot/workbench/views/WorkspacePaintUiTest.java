package sabot.workbench.views;

import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

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
 * had to draw). Prints the figures; asserts that each robot is drawn where it is.
 */
class WorkspacePaintUiTest {

    static final int ROBOTS = 100;
    static final int FRAMES = 60;

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
        Display d = canvas.getDisplay();
        long[] cpu = new long[FRAMES];
        long[] wall = new long[FRAMES];
        long[] total = new long[FRAMES];
        for (int f = -10; f < FRAMES; f++) { // 10 frames to warm up the JIT and the X server's caches
            at = Instant.now();
            for (int i = 0; i < ROBOTS; i++) {
                RobotState r = fleet.get(DrivenFleet.jid(i));
                fleet.put(r.withPose(DrivenFleet.pose(FleetViewUpdatesUiTest.x(i) + 0.002 * f, FleetViewUpdatesUiTest
                        .y(i), 0.01 * f, at), at));
            }
            FleetViewUpdatesUiTest.drain();
            int frames0 = workspace.frameCount();
            canvas.redraw();
            FleetViewUpdatesUiTest.waitFor(() -> workspace.frameCount() > frames0, 5, () -> "no paint");
            d.getCursorLocation(); // a round trip: the X server answers once it has done what came before
            long t1 = System.nanoTime();
            if (f >= 0) {
                cpu[f] = workspace.frameCpuTimesNanos()[workspace.frameCpuTimesNanos().length - 1];
                wall[f] = workspace.frameTimesNanos()[workspace.frameTimesNanos().length - 1];
                total[f] = wall[f] + t1 - workspace.lastPaintEndNanos();
            }
        }
        System.out.printf(Locale.ROOT, "[figure] Workspace paint, %d robots on a mission, %dx%d, no load: UI-thread "
                + "CPU %s; paint wall %s; paint and the X server's round trip after it %s%n", ROBOTS, canvas.getSize().x, canvas
                        .getSize().y, stats(cpu), stats(wall), stats(total));

        // what is drawn: the footprint's fill (blue) half a radius behind each of a few robots' centres
        MapViewport v = workspace.viewport();
        Image shot = new Image(d, canvas.getSize().x, canvas.getSize().y);
        GC gc = new GC(canvas);
        gc.copyArea(shot, 0, 0);
        gc.dispose();
        ImageData data = shot.getImageData();
        shot.dispose();
        for (int i : new int[] { 0, 37, 99 }) {
            RobotState r = fleet.get(DrivenFleet.jid(i));
            double behind = 0.5 * WorkspaceView.FOOTPRINT_RADIUS_M;
            int px = (int) Math.round(v.toScreenX(r.pose().pose().x() - behind * Math.cos(r.pose().pose().theta())));
            int py = (int) Math.round(v.toScreenY(r.pose().pose().y() - behind * Math.sin(r.pose().pose().theta())));
            RGB at2 = data.palette.getRGB(data.getPixel(px, py));
            assertTrue(at2.blue > at2.red + 40, "robot " + i + " not drawn at " + px + "," + py + ": " + at2);
        }
    }

    private static String stats(long[] nanos) {
        long[] s = nanos.clone();
        Arrays.sort(s);
        return String.format(Locale.ROOT, "p50 %.2f ms, p90 %.2f ms, max %.2f ms", s[s.length / 2] / 1e6, s[(int) (s.length
                * 0.9)] / 1e6, s[s.length - 1] / 1e6);
    }

    static WorkspaceView workspace() {
        WorkspaceView w = (WorkspaceView) PlatformUI.getWorkbench().getActiveWorkbenchWindow().getActivePage()
                .findView(WorkspaceView.ID);
        assertNotNull(w, "workspace view not open");
        return w;
    }
}
