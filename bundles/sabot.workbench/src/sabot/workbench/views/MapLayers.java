package sabot.workbench.views;

import org.eclipse.swt.SWT;
import org.eclipse.swt.graphics.Color;
import org.eclipse.swt.graphics.Font;
import org.eclipse.swt.graphics.GC;
import org.eclipse.swt.graphics.Image;
import org.eclipse.swt.graphics.ImageData;
import org.eclipse.swt.graphics.PaletteData;
import org.eclipse.swt.graphics.RGB;
import org.eclipse.swt.graphics.Rectangle;
import org.eclipse.swt.widgets.Display;

import sabot.controlml.payload.GridMap;
import sabot.workbench.map.MapViewport;

/**
 * The Workspace's static layers: white, the robots' map scaled, the metric grid and the frame's axes. Drawn into an
 * image of their own and redrawn only when the view moves, zooms, is resized or gets another map; each frame starts
 * as a copy of it.
 */
final class MapLayers implements AutoCloseable {

    private static final int GRID_MIN_PX = 40;

    private final MapViewport viewport;
    private GridMap map;
    private Image mapImage;
    /** Counts the maps shown, so that the cache knows when the map changed. */
    private int mapVersion;
    private MemoryImage background;
    private BackgroundKey backgroundKey;

    /** What the static layers were drawn for: the view and the map. */
    private record BackgroundKey(ViewKey view, int mapVersion) {
    }

    MapLayers(MapViewport viewport) {
        this.viewport = viewport;
    }

    /** Shows a map from the next frame on. */
    void setMap(Display display, GridMap m) {
        map = m;
        if (mapImage != null) {
            mapImage.dispose();
        }
        mapImage = new Image(display, imageOf(m));
        mapVersion++;
    }

    /** @return the map shown, or null */
    GridMap map() {
        return map;
    }

    /** Draws the static layers onto {@code gc}, after drawing them again if the view or the map changed. */
    void drawOnto(GC gc, Display d, Font font, Rectangle area, ViewKey view) {
        BackgroundKey key = new BackgroundKey(view, mapVersion);
        if (!key.equals(backgroundKey)) {
            background = MemoryImage.sized(background, d, area);
            GC layers = new GC(background.image());
            try {
                layers.setFont(font);
                layers.setAntialias(SWT.OFF);
                layers.setBackground(d.getSystemColor(SWT.COLOR_WHITE));
                layers.fillRectangle(area);
                drawMap(layers);
                drawGrid(layers, area);
                drawAxes(layers, d);
            } finally {
                layers.dispose();
            }
            backgroundKey = key;
        }
        background.drawOnto(gc);
    }

    @Override
    public void close() {
        if (mapImage != null) {
            mapImage.dispose();
        }
        if (background != null) {
            background.close();
        }
    }

    /** An 8-bit grey image of a grid, row 0 at the top (the grid's row 0 is at the bottom). */
    private static ImageData imageOf(GridMap m) {
        RGB[] greys = new RGB[256];
        for (int i = 0; i < 256; i++) {
            greys[i] = new RGB(i, i, i);
        }
        ImageData data = new ImageData(m.width(), m.height(), 8, new PaletteData(greys));
        byte[] cells = m.cells();
        byte[] line = new byte[m.width()];
        for (int row = 0; row < m.height(); row++) {
            for (int col = 0; col < m.width(); col++) {
                int v = cells[row * m.width() + col];
                // map_server's look: free white, occupied black, unknown mid grey (a lighter one: less ink)
                line[col] = (byte) (v < 0 ? 214 : 255 - Math.round(v * 2.3f));
            }
            data.setPixels(0, m.height() - 1 - row, m.width(), line, 0);
        }
        return data;
    }

    private void drawMap(GC gc) {
        if (mapImage == null) {
            return;
        }
        double res = map.resolution();
        int x0 = (int) Math.round(viewport.toScreenX(map.origin().x()));
        int y1 = (int) Math.round(viewport.toScreenY(map.origin().y() + map.height() * res));
        int w = (int) Math.round(map.width() * res * viewport.scale());
        int h = (int) Math.round(map.height() * res * viewport.scale());
        gc.setInterpolation(SWT.NONE); // crisp cells when zoomed in
        gc.drawImage(mapImage, 0, 0, map.width(), map.height(), x0, y1, w, h);
    }

    private void drawGrid(GC gc, Rectangle area) {
        double step = viewport.niceStep(GRID_MIN_PX);
        Color minor = new Color(232, 236, 240);
        Color major = new Color(200, 208, 216);
        // over a map the grid is drawn lightly, so the walls stay readable
        gc.setAlpha(mapImage != null ? 110 : 255);
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
            gc.setAlpha(255);
            minor.dispose();
            major.dispose();
        }
    }

    private static boolean isMajor(double v, double step) {
        return Math.abs(Math.IEEEremainder(v, 5 * step)) < step / 2;
    }

    private void drawAxes(GC gc, Display d) {
        int ox = (int) Math.round(viewport.toScreenX(0));
        int oy = (int) Math.round(viewport.toScreenY(0));
        int len = 60;
        gc.setLineWidth(2);
        gc.setForeground(d.getSystemColor(SWT.COLOR_DARK_RED));
        gc.drawLine(ox, oy, ox + len, oy);
        gc.drawString("x", ox + len + 3, oy - 8, true);
        gc.setForeground(d.getSystemColor(SWT.COLOR_DARK_GREEN));
        gc.drawLine(ox, oy, ox, oy - len);
        gc.drawString("y", ox - 4, oy - len - 16, true);
        gc.setLineWidth(1);
    }
}
