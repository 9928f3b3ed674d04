package sabot.workbench.pid.internal;

import java.time.Duration;
import java.time.Instant;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Deque;
import java.util.List;
import java.util.Locale;

import org.eclipse.swt.SWT;
import org.eclipse.swt.layout.GridData;
import org.eclipse.swt.layout.GridLayout;
import org.eclipse.swt.widgets.Button;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Control;
import org.eclipse.swt.widgets.Label;
import org.eclipse.swt.widgets.Text;
import org.eclipse.swtchart.Chart;
import org.eclipse.swtchart.ILineSeries;
import org.eclipse.swtchart.ISeries;

import sabot.controlml.Resources;
import sabot.controlml.payload.MotorGains;
import sabot.controlml.payload.PidGains;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.robotview.RobotView;

/**
 * PID tuning of a robot's wheel speed loops: the gains of each motor read and written with {@code cm.pid} (the robot
 * writes them to its motor board and answers with what the board holds), and a live plot (Eclipse SWTChart) of the
 * twist the robot executes, from its {@code cm.velocity} telemetry, over the last {@link #WINDOW}. The step test of the
 * issue needs a robot-side resource that does not exist yet (a step on one wheel sampled on the robot): not here.
 */
public final class PidView extends RobotView {

    public static final String ID = "sabot.workbench.pid.view";
    /** Time span of the plot. */
    public static final Duration WINDOW = Duration.ofSeconds(20);
    static final String[] COLUMNS = { "Motor", "Kp", "Ki", "Kd" };

    private Composite gainsGrid;
    private final List<Text[]> rows = new ArrayList<>();
    private final List<Integer> motors = new ArrayList<>();
    private PidGains read;
    private Chart chart;
    private final Deque<double[]> samples = new ArrayDeque<>();
    private Instant lastSample;

    @Override
    protected void createContent(Composite parent) {
        parent.setLayout(new GridLayout(1, false));
        gainsGrid = new Composite(parent, SWT.NONE);
        gainsGrid.setLayout(new GridLayout(COLUMNS.length, true));
        gainsGrid.setLayoutData(new GridData(SWT.FILL, SWT.TOP, true, false));
        Composite buttons = new Composite(parent, SWT.NONE);
        buttons.setLayout(new GridLayout(2, true));
        Button readButton = new Button(buttons, SWT.PUSH);
        readButton.setText("Read gains");
        readButton.addListener(SWT.Selection, e -> readGains());
        Button writeButton = new Button(buttons, SWT.PUSH);
        writeButton.setText("Write gains");
        writeButton.addListener(SWT.Selection, e -> {
            try {
                writeGains(edited());
            } catch (IllegalArgumentException bad) {
                showMessage(bad.getMessage(), true);
            }
        });
        chart = new Chart(parent, SWT.NONE);
        GridData g = new GridData(SWT.FILL, SWT.FILL, true, true);
        g.heightHint = 220;
        chart.setLayoutData(g);
        chart.getTitle().setText("Executed twist (cm.velocity telemetry)");
        chart.getAxisSet().getXAxis(0).getTitle().setText("time (s)");
        chart.getAxisSet().getYAxis(0).getTitle().setText("m/s, rad/s");
        series("linear (m/s)", SWT.COLOR_DARK_BLUE);
        series("angular (rad/s)", SWT.COLOR_DARK_RED);
        showGains(null);
    }

    private void series(String name, int colour) {
        ILineSeries<?> s = (ILineSeries<?>) chart.getSeriesSet().createSeries(ISeries.SeriesType.LINE, name);
        s.setLineColor(chart.getDisplay().getSystemColor(colour));
        s.setSymbolType(ILineSeries.PlotSymbolType.NONE);
    }

    @Override
    protected void robotChanged(RobotState state, boolean newRobot) {
        if (newRobot) {
            samples.clear();
            lastSample = null;
            showGains(null);
            if (state != null) {
                readGains();
            }
        }
        if (state != null && state.velocity() != null && state.lastTelemetry() != null && !state.lastTelemetry()
                .equals(lastSample)) {
            lastSample = state.lastTelemetry();
            double t = lastSample.toEpochMilli() / 1000.0;
            samples.addLast(new double[] { t, state.velocity().linear(), state.velocity().angular() });
            while (samples.size() > 1 && samples.peekFirst()[0] < t - WINDOW.toSeconds()) {
                samples.removeFirst();
            }
            plot();
        }
    }

    private void plot() {
        if (chart.isDisposed() || samples.isEmpty()) {
            return;
        }
        double end = samples.peekLast()[0];
        double[] x = new double[samples.size()];
        double[] linear = new double[x.length];
        double[] angular = new double[x.length];
        int i = 0;
        for (double[] s : samples) {
            x[i] = s[0] - end;
            linear[i] = s[1];
            angular[i++] = s[2];
        }
        ISeries<?>[] series = chart.getSeriesSet().getSeries();
        series[0].setXSeries(x);
        series[0].setYSeries(linear);
        series[1].setXSeries(x);
        series[1].setYSeries(angular);
        chart.getAxisSet().adjustRange();
        chart.redraw();
    }

    /** Reads the gains from the robot (its motor board's, as the robot holds them). */
    public void readGains() {
        request("read gains", (fleet, jid) -> fleet.get(jid, Resources.PID), this::showGains);
    }

    /** Writes gains; the robot's read-back (or, without one, a fresh read) is shown. */
    public void writeGains(PidGains gains) {
        request("write gains", (fleet, jid) -> fleet.set(jid, Resources.PID, gains), back -> {
            if (back != null) {
                showGains(back);
            } else {
                readGains();
            }
        });
    }

    /** @return the gains typed in the grid, for the motors last read */
    PidGains edited() {
        List<MotorGains> m = new ArrayList<>();
        for (int i = 0; i < rows.size(); i++) {
            Text[] r = rows.get(i);
            m.add(new MotorGains(motors.get(i), number(r[0], "Kp"), number(r[1], "Ki"), number(r[2], "Kd")));
        }
        if (m.isEmpty()) {
            throw new IllegalArgumentException("read the gains first");
        }
        return new PidGains(m);
    }

    private static double number(Text t, String what) {
        try {
            double v = Double.parseDouble(t.getText().strip());
            if (!(v >= 0) || Double.isInfinite(v)) {
                throw new IllegalArgumentException(what + " must be a number >= 0, not '" + t.getText() + "'");
            }
            return v;
        } catch (NumberFormatException e) {
            throw new IllegalArgumentException(what + " must be a number >= 0, not '" + t.getText() + "'");
        }
    }

    private void showGains(PidGains gains) {
        read = gains;
        for (Control c : gainsGrid.getChildren()) {
            c.dispose();
        }
        rows.clear();
        motors.clear();
        for (String c : COLUMNS) {
            new Label(gainsGrid, SWT.NONE).setText(c);
        }
        if (gains != null) {
            for (MotorGains m : gains.motors()) {
                new Label(gainsGrid, SWT.NONE).setText(Integer.toString(m.motor()));
                Text[] r = { field(m.kp()), field(m.ki()), field(m.kd()) };
                rows.add(r);
                motors.add(m.motor());
            }
        }
        gainsGrid.getParent().layout(true, true);
    }

    private Text field(double v) {
        Text t = new Text(gainsGrid, SWT.BORDER | SWT.RIGHT);
        t.setText(String.format(Locale.ROOT, "%.4f", v));
        t.setLayoutData(new GridData(SWT.FILL, SWT.CENTER, true, false));
        return t;
    }

    /** @return the gains last read from (or written back by) the robot, or null */
    public PidGains gains() {
        return read;
    }

    /** Types gains into the grid (as the operator does), motor by motor in the order shown. */
    public void type(PidGains gains) {
        for (MotorGains m : gains.motors()) {
            int i = motors.indexOf(m.motor());
            if (i < 0) {
                throw new IllegalArgumentException("motor " + m.motor() + " is not shown");
            }
            rows.get(i)[0].setText(Double.toString(m.kp()));
            rows.get(i)[1].setText(Double.toString(m.ki()));
            rows.get(i)[2].setText(Double.toString(m.kd()));
        }
    }

    /** Writes what the grid shows (the Write button). */
    public void writeTyped() {
        writeGains(edited());
    }

    /** @return how many telemetry samples the plot holds */
    public int plotted() {
        return samples.size();
    }

    /** @return the chart */
    public Chart chart() {
        return chart;
    }
}
