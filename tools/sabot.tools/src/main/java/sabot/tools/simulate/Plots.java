package sabot.tools.simulate;

import java.awt.BasicStroke;
import java.awt.Color;
import java.io.IOException;
import java.io.OutputStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;

import org.knowm.xchart.BitmapEncoder;
import org.knowm.xchart.BitmapEncoder.BitmapFormat;
import org.knowm.xchart.XYChart;
import org.knowm.xchart.XYChartBuilder;
import org.knowm.xchart.XYSeries;
import org.knowm.xchart.XYSeries.XYSeriesRenderStyle;
import org.knowm.xchart.style.Styler.LegendPosition;
import org.knowm.xchart.style.markers.SeriesMarkers;

import sabot.motion.sim.Trace;

/** PNG plots of a simulation trace, drawn with XChart (headless; no SWT). */
public final class Plots {

    private static final int WIDTH = 900;
    private static final int HEIGHT = 700;
    private static final Color REFERENCE = new Color(120, 120, 120);
    private static final Color TRUTH = new Color(31, 119, 180);
    private static final Color ESTIMATE = new Color(255, 127, 14);
    private static final BasicStroke DASHED = new BasicStroke(1.5f, BasicStroke.CAP_BUTT, BasicStroke.JOIN_ROUND, 1f,
            new float[] { 6f, 4f }, 0f);

    private Plots() {
    }

    /** Path plot, equal axes: reference (grey), true path (blue), estimate (orange, dashed). */
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
        XYChart chart = chart(title, "x (m)", "y (m)");
        // equal axes: one metre is as long in x as in y, so that a circle looks round (plot area aspect W:H)
        double span = Math.max(Math.max(maxX - minX, maxY - minY), 0.1) * 1.1;
        double cx = (minX + maxX) / 2, cy = (minY + maxY) / 2;
        double aspect = (double) WIDTH / HEIGHT;
        double halfX = span / 2 * Math.max(1, aspect), halfY = span / 2 * Math.max(1, 1 / aspect);
        chart.getStyler().setXAxisMin(cx - halfX).setXAxisMax(cx + halfX).setYAxisMin(cy - halfY).setYAxisMax(cy + halfY);
        addRuns(chart, "reference", t, rx, ry, REFERENCE, new BasicStroke(3f));
        addRuns(chart, "estimate", t, ex, ey, ESTIMATE, DASHED);
        addRuns(chart, "true path", t, tx, ty, TRUTH, new BasicStroke(1.5f));
        write(chart, file);
    }

    /** Tracking error |true - reference| (blue) and estimate error |estimate - true| (orange) against time. */
    public static void writeError(Trace t, String title, Path file) throws IOException {
        int tc = Trace.column("t_s"), ec = Trace.column("error_m"), sc = Trace.column("estimate_error_m");
        double emax = 0;
        for (int r = 0; r < t.size(); r++) {
            emax = Math.max(emax, Math.max(t.get(r, ec), t.get(r, sc)));
        }
        XYChart chart = chart(title, "t (s)", "error (m)");
        chart.getStyler().setYAxisMin(0.0).setYAxisMax(Math.max(emax * 1.1, 0.005));
        addRuns(chart, "tracking error |true - reference|", t, tc, ec, TRUTH, new BasicStroke(1.5f));
        addRuns(chart, "estimate error |estimate - true|", t, tc, sc, ESTIMATE, new BasicStroke(1.5f));
        write(chart, file);
    }

    private static XYChart chart(String title, String xLabel, String yLabel) {
        XYChart chart = new XYChartBuilder().width(WIDTH).height(HEIGHT).title(title).xAxisTitle(xLabel)
                .yAxisTitle(yLabel).build();
        chart.getStyler().setDefaultSeriesRenderStyle(XYSeriesRenderStyle.Line).setLegendPosition(
                LegendPosition.InsideNW).setChartBackgroundColor(Color.WHITE).setPlotBackgroundColor(Color.WHITE)
                .setAntiAlias(true);
        return chart;
    }

    /**
     * One line per run of the trace (a scenario may repeat, e.g. UMBmark's two squares): a new run starts a new line
     * instead of joining the last point of the previous run. Only the first run's line is in the legend.
     */
    private static void addRuns(XYChart chart, String name, Trace t, int cx, int cy, Color color, BasicStroke stroke) {
        int run = Trace.column("run");
        List<Double> xs = new ArrayList<>();
        List<Double> ys = new ArrayList<>();
        double lastRun = Double.NaN;
        int lines = 0;
        for (int r = 0; r <= t.size(); r++) {
            boolean end = r == t.size();
            if ((end || t.get(r, run) != lastRun) && !xs.isEmpty()) {
                XYSeries series = chart.addSeries(lines == 0 ? name : name + " (run " + (lines + 1) + ")", xs, ys);
                series.setMarker(SeriesMarkers.NONE);
                series.setLineColor(color);
                series.setLineStyle(stroke);
                series.setShowInLegend(lines == 0);
                lines++;
                xs = new ArrayList<>();
                ys = new ArrayList<>();
            }
            if (end) {
                break;
            }
            lastRun = t.get(r, run);
            xs.add(t.get(r, cx));
            ys.add(t.get(r, cy));
        }
    }

    private static void write(XYChart chart, Path file) throws IOException {
        try (OutputStream out = Files.newOutputStream(file)) {
            BitmapEncoder.saveBitmap(chart, out, BitmapFormat.PNG);
        }
    }
}
