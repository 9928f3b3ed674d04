package sabot.workbench.views;

import org.eclipse.swt.SWT;
import org.eclipse.swt.widgets.Canvas;
import org.eclipse.swt.widgets.Event;

import sabot.workbench.map.MapViewport;

/**
 * Moving about the Workspace's map: the wheel zooms at the pointer, + and - at the centre; a drag pans (the view
 * decides which presses start one), as do the arrow keys; Home (the key or a call) shows the default area.
 */
final class MapNavigation {

    /** Area shown at start and on Home: a 10 m × 10 m lab floor from the map origin. */
    private static final double[] HOME = { -1, -1, 11, 11 };
    private static final double WHEEL_ZOOM = 1.2;
    /** How far an arrow key pans, pixels. */
    private static final int KEY_STEP_PX = 40;

    private final MapViewport viewport;
    private final Canvas canvas;
    /** Where the pan drag under way was last, or null. */
    private int[] dragFrom;
    private boolean homed;

    /** Listens to the canvas's size, wheel and movements; the view forwards presses, releases and keys. */
    MapNavigation(MapViewport viewport, Canvas canvas) {
        this.viewport = viewport;
        this.canvas = canvas;
        canvas.addListener(SWT.Resize, e -> {
            var r = canvas.getClientArea();
            viewport.setCanvasSize(r.width, r.height);
            if (!homed && r.width > 0 && r.height > 0) {
                home();
                homed = true;
            }
        });
        canvas.addListener(SWT.MouseVerticalWheel, e -> {
            viewport.zoomAt(Math.pow(WHEEL_ZOOM, Math.signum(e.count)), e.x, e.y);
            canvas.redraw();
        });
    }

    /** A pan drag starts at a pixel. */
    void startPan(int x, int y) {
        dragFrom = new int[] { x, y };
    }

    /** The pointer moved: pans if a drag is under way. */
    void moved(int x, int y) {
        if (dragFrom != null) {
            viewport.panByPixels(x - dragFrom[0], y - dragFrom[1]);
            dragFrom = new int[] { x, y };
        }
    }

    /** The button went up: the drag, if any, ends. */
    void endPan() {
        dragFrom = null;
    }

    /** @return true if the key moved or zoomed the view (arrows, Home, +, =, -) */
    boolean key(Event e) {
        switch (e.keyCode) {
            case SWT.ARROW_LEFT -> viewport.panByPixels(KEY_STEP_PX, 0);
            case SWT.ARROW_RIGHT -> viewport.panByPixels(-KEY_STEP_PX, 0);
            case SWT.ARROW_UP -> viewport.panByPixels(0, KEY_STEP_PX);
            case SWT.ARROW_DOWN -> viewport.panByPixels(0, -KEY_STEP_PX);
            case SWT.HOME -> home();
            default -> {
                if (e.character == '+' || e.character == '=') {
                    viewport.zoomAt(WHEEL_ZOOM, viewport.width() / 2.0, viewport.height() / 2.0);
                } else if (e.character == '-') {
                    viewport.zoomAt(1 / WHEEL_ZOOM, viewport.width() / 2.0, viewport.height() / 2.0);
                } else {
                    return false;
                }
            }
        }
        return true;
    }

    /** Shows the default area. */
    void home() {
        viewport.fit(HOME[0], HOME[1], HOME[2], HOME[3], 20);
        if (!canvas.isDisposed()) {
            canvas.redraw();
        }
    }

    /** Centres the view on a map point. */
    void centreOn(double x, double y) {
        viewport.panByPixels(viewport.width() / 2.0 - viewport.toScreenX(x), viewport.height() / 2.0 - viewport
                .toScreenY(y));
        canvas.redraw();
    }
}
