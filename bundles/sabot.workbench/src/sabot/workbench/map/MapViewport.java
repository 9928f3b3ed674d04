package sabot.workbench.map;

/**
 * The mapping between the map frame (metres, right-handed, y up) and a canvas (pixels, y down) for the workspace
 * view: a scale in pixels per metre and the map point shown at the canvas centre. Pan moves that point, zoom
 * changes the scale while keeping the map point under the cursor fixed. Free of SWT so it is tested headless.
 */
public final class MapViewport {

    /** Closest zoom, in pixels per metre (1 px = 2 mm). */
    public static final double MAX_SCALE = 500;
    /** Farthest zoom, in pixels per metre (1 px = 10 m: a 10 km site fits a 1000 px canvas). */
    public static final double MIN_SCALE = 0.1;

    private double scale;
    private double centerX;
    private double centerY;
    private int width;
    private int height;

    /**
     * @param pixelsPerMetre initial scale, clamped to [{@link #MIN_SCALE}, {@link #MAX_SCALE}]
     * @param centerX        map x shown at the canvas centre, metres
     * @param centerY        map y shown at the canvas centre, metres
     */
    public MapViewport(double pixelsPerMetre, double centerX, double centerY) {
        this.scale = clampScale(pixelsPerMetre);
        this.centerX = centerX;
        this.centerY = centerY;
    }

    /** Sets the canvas size in pixels (negative sizes count as 0). */
    public void setCanvasSize(int widthPx, int heightPx) {
        this.width = Math.max(0, widthPx);
        this.height = Math.max(0, heightPx);
    }

    /** @return pixels per metre */
    public double scale() {
        return scale;
    }

    public double centerX() {
        return centerX;
    }

    public double centerY() {
        return centerY;
    }

    public int width() {
        return width;
    }

    public int height() {
        return height;
    }

    /** @return canvas x in pixels of a map x in metres */
    public double toScreenX(double mapX) {
        return width / 2.0 + (mapX - centerX) * scale;
    }

    /** @return canvas y in pixels (down) of a map y in metres (up) */
    public double toScreenY(double mapY) {
        return height / 2.0 - (mapY - centerY) * scale;
    }

    /** @return map x in metres under canvas x in pixels */
    public double toMapX(double screenX) {
        return centerX + (screenX - width / 2.0) / scale;
    }

    /** @return map y in metres under canvas y in pixels */
    public double toMapY(double screenY) {
        return centerY - (screenY - height / 2.0) / scale;
    }

    /** Moves the view by a drag of (dx, dy) pixels: the map follows the pointer. */
    public void panByPixels(double dx, double dy) {
        if (!Double.isFinite(dx) || !Double.isFinite(dy)) {
            return;
        }
        centerX -= dx / scale;
        centerY += dy / scale;
    }

    /**
     * Multiplies the scale by {@code factor} (clamped to the limits) keeping the map point under the canvas pixel
     * (px, py) where it is: zoom towards the mouse, as map tools do.
     */
    public void zoomAt(double factor, double px, double py) {
        if (!(factor > 0) || !Double.isFinite(factor) || !Double.isFinite(px) || !Double.isFinite(py)) {
            return;
        }
        double mx = toMapX(px);
        double my = toMapY(py);
        scale = clampScale(scale * factor);
        centerX = mx - (px - width / 2.0) / scale;
        centerY = my + (py - height / 2.0) / scale;
    }

    /** Centres the view on a rectangle of the map and picks the scale that shows it whole with a margin. */
    public void fit(double minX, double minY, double maxX, double maxY, double marginPx) {
        double w = Math.max(maxX - minX, 1e-3);
        double h = Math.max(maxY - minY, 1e-3);
        double usableW = Math.max(1, width - 2 * marginPx);
        double usableH = Math.max(1, height - 2 * marginPx);
        scale = clampScale(Math.min(usableW / w, usableH / h));
        centerX = (minX + maxX) / 2;
        centerY = (minY + maxY) / 2;
    }

    /**
     * A "nice" grid spacing or scale-bar length: the smallest 1, 2 or 5 × 10^k metres that is at least
     * {@code minPixels} long on screen at the current scale.
     *
     * @return metres
     */
    public double niceStep(double minPixels) {
        double raw = minPixels / scale;
        double decade = Math.pow(10, Math.floor(Math.log10(raw)));
        for (double m : new double[] { 1, 2, 5, 10 }) {
            if (m * decade >= raw - 1e-12) {
                return m * decade;
            }
        }
        return 10 * decade;
    }

    /** @return a length in metres written for a scale bar: "20 cm", "1 m", "50 m", "2 km" */
    public static String formatLength(double metres) {
        if (metres >= 1000) {
            return trim(metres / 1000) + " km";
        }
        if (metres >= 1) {
            return trim(metres) + " m";
        }
        if (metres >= 0.01) {
            return trim(metres * 100) + " cm";
        }
        return trim(metres * 1000) + " mm";
    }

    private static String trim(double v) {
        double r = Math.round(v * 1000) / 1000.0;
        return r == Math.rint(r) ? Long.toString((long) r) : Double.toString(r);
    }

    private static double clampScale(double s) {
        if (!Double.isFinite(s) || s <= 0) {
            return MIN_SCALE;
        }
        return Math.max(MIN_SCALE, Math.min(MAX_SCALE, s));
    }
}
