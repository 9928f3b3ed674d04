package sabot.motion.sim;

import java.awt.BasicStroke;
import java.awt.Color;
import java.awt.Font;
import java.awt.Graphics2D;
import java.awt.RenderingHints;
import java.awt.geom.Path2D;
import java.awt.image.BufferedImage;
import java.io.IOException;
import java.nio.file.Path;
import java.util.Locale;

import javax.imageio.ImageIO;

/** PNG plots drawn with java.awt on a BufferedImage (headless; no SWT). */
public final class Plots {

    private static final int W = 900;
    private static final int H = 700;
    private static final int MARGIN = 70;
    private static final Color REFERENCE = new Color(120, 120, 120);
    private static final Color TRUTH = new Color(31, 119, 180);
    private static final Color ESTIMATE = new Color(255, 127, 14);

    private Plots() {
    }

    /** Path plot, equal axes: reference (grey), true path (blue), estimate (orange). */
    public static void writePath(Trace t, String title, Path file) throws IOException {
        int rx = Trace.column("ref_x_m"), ry = Trace.column("ref_y_m");
        int tx = Trace.column("true_x_m"), ty = Trace.column("true_y_m");
        int ex = Trace.column("est_x_m"), ey = Trace.column("est_y_m");
        double minX = Double.POSITIVE_INFINITY, maxX = Double.NEGATIVE_INFINITY;
        double minY = Double.POSITIVE_INFINITY, maxY = Double.NEGATIVE_INFINITY;
        for (int r = 0; r < t.size(); r++) {
            for (int[] c : new int[][] { { rx, ry }, { tx, ty }, { ex, ey } }) {
                minX = Math.min(minX, t.get(r, c[0]));
                maxX = Math.max(maxX, t.get(r, c[0]));
                minY = Math.min(minY, t.get(r, c[1]));
                maxY = Math.max(maxY, t.get(r, c[1]));
            }
        }
        double span = Math.max(Math.max(maxX - minX, maxY - minY), 0.1) * 1.1;
        double cx = (minX + maxX) / 2, cy = (minY + maxY) / 2;
        double scale = Math.min(W - 2 * MARGIN, H - 2 * MARGIN) / span;
        Frame f = new Frame(title, "x (m)", "y (m)");
        f.axes(cx - (W - 2 * MARGIN) / scale / 2, cx + (W - 2 * MARGIN) / scale / 2,
                cy - (H - 2 * MARGIN) / scale / 2, cy + (H - 2 * MARGIN) / scale / 2);
        f.series(t, rx, ry, REFERENCE, 3f, false);
        f.series(t, ex, ey, ESTIMATE, 1.5f, true);
        f.series(t, tx, ty, TRUTH, 1.5f, false);
        f.legend(new String[] { "reference", "true path", "estimate" }, new Color[] { REFERENCE, TRUTH, ESTIMATE });
        f.write(file);
    }

    /** Tracking error |true - reference| (blue) and estimate error |estimate - true| (orange) against time. */
    public static void writeError(Trace t, String title, Path file) throws IOException {
        int tc = Trace.column("t_s"), ec = Trace.column("error_m"), sc = Trace.column("estimate_error_m");
        double t0 = Double.POSITIVE_INFINITY, t1 = Double.NEGATIVE_INFINITY, emax = 0;
        for (int r = 0; r < t.size(); r++) {
            t0 = Math.min(t0, t.get(r, tc));
            t1 = Math.max(t1, t.get(r, tc));
            emax = Math.max(emax, Math.max(t.get(r, ec), t.get(r, sc)));
        }
        Frame f = new Frame(title, "t (s)", "error (m)");
        f.axes(t0, t1, 0, Math.max(emax * 1.1, 0.005));
        f.series(t, tc, ec, TRUTH, 1.5f, false);
        f.series(t, tc, sc, ESTIMATE, 1.5f, false);
        f.legend(new String[] { "tracking error |true - reference|", "estimate error |estimate - true|" },
                new Color[] { TRUTH, ESTIMATE });
        f.write(file);
    }

    /** A plotting area with axes, ticks and labels. */
    private static final class Frame {
        private final BufferedImage image = new BufferedImage(W, H, BufferedImage.TYPE_INT_RGB);
        private final Graphics2D g = image.createGraphics();
        private double x0, x1, y0, y1;

        Frame(String title, String xLabel, String yLabel) {
            g.setRenderingHint(RenderingHints.KEY_ANTIALIASING, RenderingHints.VALUE_ANTIALIAS_ON);
            g.setColor(Color.WHITE);
            g.fillRect(0, 0, W, H);
            g.setColor(Color.BLACK);
            g.setFont(new Font(Font.SANS_SERIF, Font.BOLD, 16));
            g.drawString(title, MARGIN, 30);
            g.setFont(new Font(Font.SANS_SERIF, Font.PLAIN, 13));
            g.drawString(xLabel, W / 2 - 20, H - 20);
            g.rotate(-Math.PI / 2);
            g.drawString(yLabel, -H / 2 - 30, 20);
            g.rotate(Math.PI / 2);
        }

        void axes(double xa, double xb, double ya, double yb) {
            x0 = xa;
            x1 = xb;
            y0 = ya;
            y1 = yb;
            g.setColor(new Color(235, 235, 235));
            double sx = step(x1 - x0), sy = step(y1 - y0);
            g.setFont(new Font(Font.SANS_SERIF, Font.PLAIN, 11));
            for (double v = Math.ceil(x0 / sx) * sx; v <= x1; v += sx) {
                g.setColor(new Color(230, 230, 230));
                g.drawLine(px(v), MARGIN, px(v), H - MARGIN);
                g.setColor(Color.DARK_GRAY);
                g.drawString(fmt(v), px(v) - 12, H - MARGIN + 16);
            }
            for (double v = Math.ceil(y0 / sy) * sy; v <= y1; v += sy) {
                g.setColor(new Color(230, 230, 230));
                g.drawLine(MARGIN, py(v), W - MARGIN, py(v));
                g.setColor(Color.DARK_GRAY);
                g.drawString(fmt(v), 28, py(v) + 4);
            }
            g.setColor(Color.BLACK);
            g.drawRect(MARGIN, MARGIN, W - 2 * MARGIN, H - 2 * MARGIN);
        }

        void series(Trace t, int cx, int cy, Color color, float width, boolean dashed) {
            Path2D.Double p = new Path2D.Double();
            int run = Trace.column("run");
            double lastRun = Double.NaN;
            for (int r = 0; r < t.size(); r++) {
                double x = px(t.get(r, cx)), y = py(t.get(r, cy));
                if (t.get(r, run) != lastRun) {
                    p.moveTo(x, y);
                    lastRun = t.get(r, run);
                } else {
                    p.lineTo(x, y);
                }
            }
            g.setColor(color);
            g.setStroke(dashed ? new BasicStroke(width, BasicStroke.CAP_BUTT, BasicStroke.JOIN_ROUND, 1f,
                    new float[] { 6f, 4f }, 0f) : new BasicStroke(width));
            g.setClip(MARGIN, MARGIN, W - 2 * MARGIN, H - 2 * MARGIN);
            g.draw(p);
            g.setClip(null);
            g.setStroke(new BasicStroke(1f));
        }

        void legend(String[] names, Color[] colors) {
            g.setFont(new Font(Font.SANS_SERIF, Font.PLAIN, 12));
            for (int i = 0; i < names.length; i++) {
                int y = MARGIN + 18 + 18 * i;
                g.setColor(colors[i]);
                g.fillRect(MARGIN + 10, y - 9, 20, 4);
                g.setColor(Color.BLACK);
                g.drawString(names[i], MARGIN + 36, y - 3);
            }
        }

        void write(Path file) throws IOException {
            g.dispose();
            if (!ImageIO.write(image, "png", file.toFile())) {
                throw new IOException("no PNG writer available");
            }
        }

        private int px(double x) {
            return (int) Math.round(MARGIN + (x - x0) / (x1 - x0) * (W - 2 * MARGIN));
        }

        private int py(double y) {
            return (int) Math.round(H - MARGIN - (y - y0) / (y1 - y0) * (H - 2 * MARGIN));
        }

        private static double step(double range) {
            double raw = range / 8;
            double mag = Math.pow(10, Math.floor(Math.log10(raw)));
            double n = raw / mag;
            return (n < 1.5 ? 1 : n < 3.5 ? 2 : n < 7.5 ? 5 : 10) * mag;
        }

        private static String fmt(double v) {
            return Math.abs(v) < 1e-12 ? "0" : String.format(Locale.ROOT, "%.3g", v);
        }
    }
}
