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
import sabot.controlml.Role;
import sabot.controlml.payload.MotorGains;
import sabot.controlml.payload.PidGains;
import sabot.pidstep.StepFigures;
import sabot.pidstep.StepSample;
import sabot.pidstep.controlml.PidStep;
import sabot.pidstep.controlml.StepTest;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.robotview.RobotView;

/**
 * PID tuning of a robot's wheel speed loops: the gains of each motor read and written with {@code cm.pid} (the robot
 * writes them to its motor board and answers with what the board holds), and a live plot (Eclipse SWTChart) of the
 * twist the robot executes, from its {@code cm.velocity} telemetry, over the last {@link #WINDOW}.
 * <p>
 * <b>Step test</b> ({@code cm.pid.step}, a resource the robot adds to ControlML, {@link PidStep}): the robot, in
 * maintenance, steps the position loop of the chosen wheel and its motor board records the response; the view plots
 * measured position and set-point against time and shows rise time, overshoot and settling ({@link StepFigures}). The
 * previous test stays on the plot, dashed, so two gain sets are compared by writing the second set and testing again.
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
    private Chart stepChart;
    private org.eclipse.swt.widgets.Combo wheel;
    private Text stepSize;
    private Label figuresLabel;
    private StepTest lastStep;
    private StepTest previousStep;
    /** Wheels as {@code cm.pid} numbers them on a SabotOne. */
    static final String[] WHEELS = { "0 (left)", "1 (right)" };
    private final Deque<double[]> samples = new ArrayDeque<>();
    /** What changes the robot: the maintainer's (docs/CONTROLML.md section 9). */
    private Button writeButton;
    private Button stepButton;
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
        writeButton = new Button(buttons, SWT.PUSH);
        writeButton.setText("Write gains");
        writeButton.addListener(SWT.Selection, e -> {
            try {
                writeGains(edited());
            } catch (IllegalArgumentException bad) {
                showMessage(bad.getMessage(), true);
            }
        });
        Composite step = new Composite(parent, SWT.NONE);
        step.setLayout(new GridLayout(6, false));
        step.setLayoutData(new GridData(SWT.FILL, SWT.TOP, true, false));
        new Label(step, SWT.NONE).setText("Wheel");
        wheel = new org.eclipse.swt.widgets.Combo(step, SWT.READ_ONLY);
        wheel.setItems(WHEELS);
        wheel.select(0);
        new Label(step, SWT.NONE).setText("Step (mm)");
        stepSize = new Text(step, SWT.BORDER | SWT.RIGHT);
        stepSize.setText("2");
        stepSize.setLayoutData(new GridData(60, SWT.DEFAULT));
        stepButton = new Button(step, SWT.PUSH);
        stepButton.setText("Step test");
        stepButton.addListener(SWT.Selection, e -> {
            try {
                stepTest(wheel.getSelectionIndex(), millimetres(stepSize) / 1000);
            } catch (IllegalArgumentException bad) {
                showMessage(bad.getMessage(), true);
            }
        });
        figuresLabel = new Label(step, SWT.NONE);
        figuresLabel.setText("in maintenance only: the robot moves one wheel by the step");
        // a line of its own: two tests' figures side by side are wider than the controls
        figuresLabel.setLayoutData(new GridData(SWT.FILL, SWT.CENTER, true, false, 6, 1));
        stepChart = new Chart(parent, SWT.NONE);
        GridData sg = new GridData(SWT.FILL, SWT.FILL, true, true);
        sg.heightHint = 220;
        stepChart.setLayoutData(sg);
        stepChart.getTitle().setText("Step response (cm.pid.step, sampled on the motor board)");
        stepChart.getAxisSet().getXAxis(0).getTitle().setText("time since the step (ms)");
        stepChart.getAxisSet().getYAxis(0).getTitle().setText("wheel position (mm)");
        chart = new Chart(parent, SWT.NONE);
        GridData g = new GridData(SWT.FILL, SWT.FILL, true, true);
        g.heightHint = 160;
        chart.setLayoutData(g);
        chart.getTitle().setText("Executed twist (cm.velocity telemetry)");
        chart.getAxisSet().getXAxis(0).getTitle().setText("time (s)");
        chart.getAxisSet().getYAxis(0).getTitle().setText("m/s, rad/s");
        series("linear (m/s)", SWT.COLOR_DARK_BLUE);
        series("angular (rad/s)", SWT.COLOR_DARK_RED);
        showGains(null);
    }

    private static double millimetres(Text t) {
        try {
            double v = Double.parseDouble(t.getText().strip());
            if (v == 0 || !Double.isFinite(v)) {
                throw new NumberFormatException();
            }
            return v;
        } catch (NumberFormatException e) {
            throw new IllegalArgumentException("the step must be a non-zero number of mm, not '" + t.getText() + "'");
        }
    }

    /**
     * Asks the robot for a step test (off the UI thread); the response is plotted over the previous one.
     *
     * @param motor the wheel's motor, as {@code cm.pid} numbers it
     * @param step  m of wheel travel
     */
    public void stepTest(int motor, double step) {
        request("step test", (fleet, jid) -> fleet.set(jid, PidStep.RESOURCE, StepTest.request(motor, step)),
                this::showStep);
    }

    private void showStep(StepTest test) {
        if (test == null || test.samples().size() < 2) {
            showMessage("the robot answered the step test without samples", true);
            return;
        }
        previousStep = lastStep;
        lastStep = test;
        for (ISeries<?> old : stepChart.getSeriesSet().getSeries()) {
            stepChart.getSeriesSet().deleteSeries(old.getId());
        }
        if (previousStep != null) {
            stepSeries("previous: measured", previousStep, false, SWT.COLOR_GRAY, SWT.LINE_DASH);
        }
        stepSeries("set-point", test, true, SWT.COLOR_DARK_GREEN, SWT.LINE_SOLID);
        stepSeries("measured", test, false, SWT.COLOR_DARK_BLUE, SWT.LINE_SOLID);
        stepChart.getAxisSet().adjustRange();
        stepChart.redraw();
        figuresLabel.setText(describe("now", test) + (previousStep == null ? "" : "   |   " + describe("before",
                previousStep)));
        figuresLabel.getParent().layout(true, true);
    }

    private void stepSeries(String name, StepTest test, boolean setPoint, int colour, int style) {
        double[] x = new double[test.samples().size()];
        double[] y = new double[x.length];
        for (int i = 0; i < x.length; i++) {
            StepSample s = test.samples().get(i);
            x[i] = s.t() * 1e3;
            y[i] = (setPoint ? s.setPoint() : s.measured()) * 1e3;
        }
        ILineSeries<?> s = (ILineSeries<?>) stepChart.getSeriesSet().createSeries(ISeries.SeriesType.LINE, name);
        s.setLineColor(stepChart.getDisplay().getSystemColor(colour));
        s.setLineStyle(style == SWT.LINE_DASH ? org.eclipse.swtchart.LineStyle.DASH
                : org.eclipse.swtchart.LineStyle.SOLID);
        s.setSymbolType(ILineSeries.PlotSymbolType.NONE);
        s.setXSeries(x);
        s.setYSeries(y);
    }

    private static String describe(String which, StepTest test) {
        StepFigures f = StepFigures.of(test.samples());
        return String.format(Locale.ROOT, "%s wheel %d, %.2f mm: rise %s, overshoot %.1f %%, settling %s", which,
                test.motor(), test.step() * 1e3, ms(f.riseTime()), f.overshoot(), ms(f.settlingTime()));
    }

    private static String ms(double seconds) {
        return Double.isNaN(seconds) ? "not reached" : String.format(Locale.ROOT, "%.1f ms", seconds * 1e3);
    }

    /** @return the last step test's answer, or null */
    public StepTest lastStep() {
        return lastStep;
    }

    /** @return the step test before it (overlaid), or null */
    public StepTest previousStep() {
        return previousStep;
    }

    /** @return the figures line under the step controls */
    public String figuresText() {
        return figuresLabel.getText();
    }

    /** @return the step-response chart */
    public Chart stepChart() {
        return stepChart;
    }

    private void series(String name, int colour) {
        ILineSeries<?> s = (ILineSeries<?>) chart.getSeriesSet().createSeries(ISeries.SeriesType.LINE, name);
        s.setLineColor(chart.getDisplay().getSystemColor(colour));
        s.setSymbolType(ILineSeries.PlotSymbolType.NONE);
    }

    @Override
    protected void robotChanged(RobotState state, boolean newRobot) {
        gate(writeButton, Role.MAINTAINER, "Writing gains");
        gate(stepButton, Role.MAINTAINER, "The step test");
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

    /** @return the Write gains button (enabled for a maintainer of the robot) */
    public Button writeButton() {
        return writeButton;
    }
}
