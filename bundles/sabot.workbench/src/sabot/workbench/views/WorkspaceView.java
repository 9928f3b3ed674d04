package sabot.workbench.views;

import org.eclipse.swt.SWT;
import org.eclipse.swt.events.MouseEvent;
import org.eclipse.swt.events.MouseListener;
import org.eclipse.swt.events.MouseMoveListener;
import org.eclipse.swt.events.PaintEvent;
import org.eclipse.swt.graphics.Color;
import org.eclipse.swt.graphics.GC;
import org.eclipse.swt.graphics.Point;
import org.eclipse.swt.graphics.Rectangle;
import org.eclipse.swt.widgets.Canvas;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Display;
import org.eclipse.ui.part.ViewPart;

import sabot.workbench.map.MapViewport;

/**
 * The shared workspace: a map canvas in the map frame (metres, y up) with a metric grid, the frame's axes and a
 * scale bar. Drag to pan, wheel to zoom at the pointer, double-click or Home to show the default area, +/- and the
 * arrow keys from the keyboard. Robots, obstacles and paths are drawn on it by later layers.
 */
public final class WorkspaceView extends ViewPart {

    public static final String ID = "sabot.workbench.views.workspace";

    /** Area shown at start and on Home: a 10 m × 10 m lab floor from the map origin. */
    private static final double[] HOME = { -1, -1, 11, 11 };
    private static final double WHEEL_ZOOM = 1.2;
    private static final int GRID_MIN_PX = 40;
    private static final int SCALE_BAR_MIN_PX = 100;

    private final MapViewport viewport = new MapViewport(50, 5, 5);
    private Canvas canvas;
    private Point dragFrom;
    private Point pointer;
    private boolean homed;

    @Override
    public void createPartControl(Composite parent) {
        canvas = new Canvas(parent, SWT.DOUBLE_BUFFERED | SWT.NO_BACKGROUND);
        canvas.addPaintListener(this::paint);
        canvas.addListener(SWT.Resize, e -> {
            Rectangle r = canvas.getClientArea();
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
        canvas.addMouseListener(new MouseListener() {
            @Override
            public void mouseDown(MouseEvent e) {
                if (e.button == 1) {
                    dragFrom = new Point(e.x, e.y);
                }
            }

            @Override
            public void mouseUp(MouseEvent e) {
                dragFrom = null;
            }

            @Override
            public void mouseDoubleClick(MouseEvent e) {
                home();
            }
        });
        canvas.addMouseMoveListener((MouseMoveListener) e -> {
            if (dragFrom != null) {
                viewport.panByPixels(e.x - dragFrom.x, e.y - dragFrom.y);
                dragFrom = new Point(e.x, e.y);
            }
            pointer = new Point(e.x, e.y);
            canvas.redraw();
        });
        canvas.addListener(SWT.KeyDown, e -> {
            int step = 40;
            switch (e.keyCode) {
                case SWT.ARROW_LEFT -> viewport.panByPixels(step, 0);
                case SWT.ARROW_RIGHT -> viewport.panByPixels(-step, 0);
                case SWT.ARROW_UP -> viewport.panByPixels(0, step);
                case SWT.ARROW_DOWN -> viewport.panByPixels(0, -step);
                case SWT.HOME -> home();
                default -> {
                    if (e.character == '+' || e.character == '=') {
                        viewport.zoomAt(WHEEL_ZOOM, viewport.width() / 2.0, viewport.height() / 2.0);
                    } else if (e.character == '-') {
                        viewport.zoomAt(1 / WHEEL_ZOOM, viewport.width() / 2.0, viewport.height() / 2.0);
                    }
                }
            }
            canvas.redraw();
        });
    }

    /** @return the viewport (for plug-ins drawing on the map and for tests) */
    public MapViewport viewport() {
        return viewport;
    }

    /** Shows the default area. */
    public void home() {
        viewport.fit(HOME[0], HOME[1], HOME[2], HOME[3], 20);
        if (canvas != null && !canvas.isDisposed()) {
            canvas.redraw();
        }
    }

    private void paint(PaintEvent e) {
        GC gc = e.gc;
        Display d = canvas.getDisplay();
        Rectangle area = canvas.getClientArea();
        gc.setAntialias(SWT.ON);
        gc.setBackground(d.getSystemColor(SWT.COLOR_WHITE));
        gc.fillRectangle(area);
        drawGrid(gc, area);
        drawAxes(gc, area);
        drawScaleBar(gc, area);
        drawPointer(gc, area);
    }

    private void drawGrid(GC gc, Rectangle area) {
        double step = viewport.niceStep(GRID_MIN_PX);
        Color minor = new Color(232, 236, 240);
        Color major = new Color(200, 208, 216);
        try {
            double x0 = Math.floor(viewport.toMapX(0) / step) * step;
            double x1 = viewport.toMapX(area.width);
            for (double x = x0; x <= x1; x += step) {
                gc.setForeground(isMajor(x, step) ? major : minor);
                int sx = (int) Math.round(viewport.toScreenX(x));
                gc.drawLine(sx, 0, sx, area.height);
            }
            double y0 = Math.floor(viewport.toMapY(area.height) / step) * step;
            double y1 = viewport.toMapY(0);
            for (double y = y0; y <= y1; y += step) {
                gc.setForeground(isMajor(y, step) ? major : minor);
                int sy = (int) Math.round(viewport.toScreenY(y));
                gc.drawLine(0, sy, area.width, sy);
            }
        } finally {
            minor.dispose();
            major.dispose();
        }
    }

    private static boolean isMajor(double v, double step) {
        return Math.abs(Math.IEEEremainder(v, 5 * step)) < step / 2;
    }

    private void drawAxes(GC gc, Rectangle area) {
        int ox = (int) Math.round(viewport.toScreenX(0));
        int oy = (int) Math.round(viewport.toScreenY(0));
        int len = 60;
        gc.setLineWidth(2);
        gc.setForeground(canvas.getDisplay().getSystemColor(SWT.COLOR_DARK_RED));
        gc.drawLine(ox, oy, ox + len, oy);
        gc.drawString("x", ox + len + 3, oy - 8, true);
        gc.setForeground(canvas.getDisplay().getSystemColor(SWT.COLOR_DARK_GREEN));
        gc.drawLine(ox, oy, ox, oy - len);
        gc.drawString("y", ox - 4, oy - len - 16, true);
        gc.setLineWidth(1);
    }

    private void drawScaleBar(GC gc, Rectangle area) {
        double metres = viewport.niceStep(SCALE_BAR_MIN_PX);
        int px = (int) Math.round(metres * viewport.scale());
        int x = 16;
        int y = area.height - 20;
        gc.setForeground(canvas.getDisplay().getSystemColor(SWT.COLOR_BLACK));
        gc.setLineWidth(2);
        gc.drawLine(x, y, x + px, y);
        gc.drawLine(x, y - 5, x, y + 5);
        gc.drawLine(x + px, y - 5, x + px, y + 5);
        gc.setLineWidth(1);
        String label = MapViewport.formatLength(metres);
        Point size = gc.textExtent(label);
        gc.drawString(label, x + (px - size.x) / 2, y - size.y - 4, true);
    }

    private void drawPointer(GC gc, Rectangle area) {
        if (pointer == null) {
            return;
        }
        String text = String.format("x %.2f m, y %.2f m", viewport.toMapX(pointer.x), viewport.toMapY(pointer.y));
        Point size = gc.textExtent(text);
        gc.setForeground(canvas.getDisplay().getSystemColor(SWT.COLOR_DARK_GRAY));
        gc.drawString(text, area.width - size.x - 12, area.height - size.y - 10, true);
    }

    @Override
    public void setFocus() {
        canvas.setFocus();
    }
}
