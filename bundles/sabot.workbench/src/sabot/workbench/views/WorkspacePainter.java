package sabot.workbench.views;

import java.time.Instant;
import java.util.ArrayList;
import java.util.List;

import org.eclipse.swt.SWT;
import org.eclipse.swt.graphics.Color;
import org.eclipse.swt.graphics.Font;
import org.eclipse.swt.graphics.GC;
import org.eclipse.swt.graphics.Point;
import org.eclipse.swt.graphics.Rectangle;
import org.eclipse.swt.widgets.Display;

import sabot.controlml.payload.Goal;
import sabot.controlml.payload.GridMap;
import sabot.model.geometry.Point2D;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.map.MapViewport;

/**
 * Paints the Workspace's frames: the static layers ({@link MapLayers}), every robot ({@link RobotPainter}), then the
 * overlays (the mission being edited, the goal gesture, the scale bar, the pointer's coordinates, the last command's
 * answer). A frame is drawn into an image in the workbench's memory, the canvas's size, so that cairo rasterizes in
 * this process and the X server receives one image a paint instead of every shape to rasterize in software (Xvfb: as
 * much CPU again as the paint; docs/WORKBENCH.md).
 */
final class WorkspacePainter implements AutoCloseable {

    private static final int SCALE_BAR_MIN_PX = 100;

    private final MapViewport viewport;
    private final MapLayers layers;
    private final RobotPainter robots;
    private MemoryImage frame;

    /**
     * What a frame shows besides the map and the robots.
     *
     * @param selected the selected robot's JID, or null
     * @param gesture  the goal the gesture under way would send, or null
     * @param pointer  the pointer on the canvas, or null
     * @param message  the last command's answer, or null
     * @param error    true when the message is a refusal or failure
     * @param mission  the mission being edited, or null
     * @param robotAt  where the edited mission's robot is (its route starts there), or null
     */
    record Overlay(String selected, Goal gesture, Point pointer, String message, boolean error, MissionEditor mission,
            Point2D robotAt) {
    }

    /** The robots a frame drew, and those of them drawn live on the map. */
    record Drawn(List<RobotState> all, List<RobotState> live) {
    }

    WorkspacePainter(MapViewport viewport) {
        this.viewport = viewport;
        this.layers = new MapLayers(viewport);
        this.robots = new RobotPainter(viewport);
    }

    /** Shows a map from the next frame on. */
    void setMap(Display display, GridMap m) {
        layers.setMap(display, m);
    }

    /** @return the map shown, or null */
    GridMap map() {
        return layers.map();
    }

    /** Draws a frame of {@code fleet} into the frame image; {@link #copyTo} then puts it on the window. */
    Drawn draw(Display d, Font font, Rectangle area, List<RobotState> fleet, Overlay overlay) {
        frame = MemoryImage.sized(frame, d, area);
        GC gc = new GC(frame.image());
        try {
            gc.setFont(font);
            return drawFrame(gc, d, font, area, fleet, overlay);
        } finally {
            gc.dispose();
        }
    }

    /** Copies the last frame drawn onto the window's {@code gc}. */
    void copyTo(GC gc) {
        frame.drawOnto(gc);
    }

    @Override
    public void close() {
        layers.close();
        robots.close();
        if (frame != null) {
            frame.close();
        }
    }

    private Drawn drawFrame(GC gc, Display d, Font font, Rectangle area, List<RobotState> fleet, Overlay overlay) {
        // antialiasing only where it shows (the footprints, RobotPainter): antialiased strokes cost cairo far more
        // than aliased ones (docs/WORKBENCH.md)
        gc.setAntialias(SWT.OFF);
        ViewKey view = new ViewKey(area.width, area.height, viewport.scale(), viewport.centerX(), viewport.centerY());
        layers.drawOnto(gc, d, font, area, view);
        Instant now = Instant.now();
        boolean mapShown = layers.map() != null;
        List<RobotState> live = new ArrayList<>();
        for (RobotState r : fleet) {
            boolean stale = r.isStale(now);
            robots.draw(gc, r, stale, r.jid().equals(overlay.selected()), view);
            if (!stale && r.pose() != null && mapShown) {
                live.add(r);
            }
        }
        robots.forgetAllBut(fleet);
        if (overlay.mission() != null) {
            MissionPainter.draw(gc, viewport, overlay.robotAt(), overlay.mission().targets(), overlay.mission()
                    .selected(), true, false);
        }
        if (overlay.gesture() != null) {
            Color c = new Color(RobotPainter.SELECTED);
            try {
                RobotPainter.drawGoal(gc, viewport, overlay.gesture().pose(), c);
            } finally {
                c.dispose();
            }
        }
        drawScaleBar(gc, d, area);
        drawPointer(gc, d, area, overlay.pointer());
        if (overlay.message() != null) {
            gc.setForeground(d.getSystemColor(overlay.error() ? SWT.COLOR_DARK_RED : SWT.COLOR_DARK_GRAY));
            gc.drawString(overlay.message(), 12, 8, true);
        }
        return new Drawn(fleet, live);
    }

    private void drawScaleBar(GC gc, Display d, Rectangle area) {
        double metres = viewport.niceStep(SCALE_BAR_MIN_PX);
        int px = (int) Math.round(metres * viewport.scale());
        int x = 16;
        int y = area.height - 20;
        gc.setForeground(d.getSystemColor(SWT.COLOR_BLACK));
        gc.setLineWidth(2);
        gc.drawLine(x, y, x + px, y);
        gc.drawLine(x, y - 5, x, y + 5);
        gc.drawLine(x + px, y - 5, x + px, y + 5);
        gc.setLineWidth(1);
        String label = MapViewport.formatLength(metres);
        Point size = gc.textExtent(label);
        gc.drawString(label, x + (px - size.x) / 2, y - size.y - 4, true);
    }

    private void drawPointer(GC gc, Display d, Rectangle area, Point pointer) {
        if (pointer == null) {
            return;
        }
        String text = String.format("x %.2f m, y %.2f m", viewport.toMapX(pointer.x), viewport.toMapY(pointer.y));
        Point size = gc.textExtent(text);
        gc.setForeground(d.getSystemColor(SWT.COLOR_DARK_GRAY));
        gc.drawString(text, area.width - size.x - 12, area.height - size.y - 10, true);
    }
}
