package sabot.workbench.statistics.internal;

import java.time.Duration;
import java.util.ArrayList;
import java.util.HashSet;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;
import java.util.TreeMap;

import org.eclipse.jface.viewers.ArrayContentProvider;
import org.eclipse.jface.viewers.ColumnLabelProvider;
import org.eclipse.jface.viewers.ISelection;
import org.eclipse.jface.viewers.IStructuredSelection;
import org.eclipse.jface.viewers.StructuredSelection;
import org.eclipse.jface.viewers.TableViewer;
import org.eclipse.jface.viewers.TableViewerColumn;
import org.eclipse.swt.SWT;
import org.eclipse.swt.custom.SashForm;
import org.eclipse.swt.layout.GridData;
import org.eclipse.swt.layout.GridLayout;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Display;
import org.eclipse.swt.widgets.Label;
import org.eclipse.swtchart.Chart;
import org.eclipse.swtchart.ILineSeries;
import org.eclipse.swtchart.ISeries;
import org.eclipse.ui.ISelectionListener;
import org.eclipse.ui.IWorkbenchPart;
import org.eclipse.ui.part.ViewPart;

import sabot.controlml.ControlMlCondition;
import sabot.workbench.fleet.FleetCommandException;
import sabot.workbench.fleet.FleetBinding;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.fleet.TrafficStatistics;

/**
 * Traffic: the workbench's own count of its traffic with each robot ({@link FleetState#traffic}, docs/STATISTICS.md)
 * as a table, one row per robot, and two plots (Eclipse SWTChart) of the selected robot over the last five minutes:
 * stanzas per second in and out, and the round-trip p99. Refreshed every {@link #REFRESH_MS} ms by a timer on the UI
 * thread, which reads in-memory snapshots only (no request, no wait on the network: the ControlML plug-in counts on
 * its own threads). The robot selected here, in the Fleet view or on the map is the one plotted.
 * <p>
 * Under the table, the server's figures of the selected robot over the last {@link #SERVER_WINDOW} (what every client
 * sent it, as the server archived it: {@link FleetState#serverStatistics}), asked for every {@link #SERVER_REFRESH_MS}
 * ms on the fleet's threads, one request at a time; a server without the archive says so once.
 */
public final class TrafficView extends ViewPart {

    public static final String ID = "sabot.workbench.statistics.view";
    /** The refresh period: the rates are per second, over whole seconds. */
    public static final int REFRESH_MS = 1000;
    /** How often the server's figures are asked for: a database query on the server each time. */
    public static final int SERVER_REFRESH_MS = 10_000;
    /** The server's figures' window. */
    public static final Duration SERVER_WINDOW = Duration.ofMinutes(15);

    private final TrafficHistory history = new TrafficHistory();
    private final ISelectionListener selectionListener = this::selectionChanged;
    private final long startNanos = System.nanoTime();
    private FleetBinding binding;
    private TableViewer table;
    private Label summary;
    private Label serverLine;
    /** The robot whose server figures were last asked for, and when (System.nanoTime), UI thread only. */
    private String serverAskedFor;
    private long serverAskedAt;
    private boolean serverAsking;
    /** The server said it keeps no archive: not asked again for this robot. */
    private boolean serverHasNoArchive;
    private Chart messages;
    private Chart roundTrip;
    private List<TrafficStatistics> rows = List.of();
    private String selected;
    private long refreshes;
    private long slowestRefreshNanos;

    @Override
    public void createPartControl(Composite parent) {
        parent.setLayout(new GridLayout(1, false));
        summary = new Label(parent, SWT.NONE);
        summary.setLayoutData(new GridData(SWT.FILL, SWT.TOP, true, false));
        serverLine = new Label(parent, SWT.NONE);
        serverLine.setLayoutData(new GridData(SWT.FILL, SWT.TOP, true, false));
        serverLine.setText("server: –");
        SashForm split = new SashForm(parent, SWT.VERTICAL);
        split.setLayoutData(new GridData(SWT.FILL, SWT.FILL, true, true));
        table = new TableViewer(split, SWT.FULL_SELECTION | SWT.BORDER | SWT.V_SCROLL | SWT.SINGLE);
        table.getTable().setHeaderVisible(true);
        table.getTable().setLinesVisible(true);
        for (TrafficTexts.Column c : TrafficTexts.COLUMNS) {
            TableViewerColumn v = new TableViewerColumn(table, c.title().equals("Robot") || c.title().equals(
                    "Errors") ? SWT.LEFT : SWT.RIGHT);
            v.getColumn().setText(c.title());
            v.getColumn().setWidth(c.width());
            v.setLabelProvider(new ColumnLabelProvider() {
                @Override
                public String getText(Object element) {
                    return c.text().apply((TrafficStatistics) element);
                }
            });
        }
        table.setContentProvider(ArrayContentProvider.getInstance());
        table.addSelectionChangedListener(e -> {
            if (e.getStructuredSelection().getFirstElement() instanceof TrafficStatistics s) {
                select(s.robot());
            }
        });
        Composite plots = new Composite(split, SWT.NONE);
        plots.setLayout(new GridLayout(2, true));
        messages = chart(plots, "Stanzas per second", "msg/s");
        line(messages, "in", SWT.COLOR_DARK_BLUE);
        line(messages, "out", SWT.COLOR_DARK_RED);
        roundTrip = chart(plots, "Round trip p99 (last minute)", "ms");
        line(roundTrip, "p99", SWT.COLOR_DARK_GREEN);
        split.setWeights(2, 3);
        binding = new FleetBinding(uiThread(parent.getDisplay()), () -> {
        }); // the robots and the service; the timer below refreshes
        getSite().getPage().addSelectionListener(selectionListener);
        parent.getDisplay().timerExec(0, this::tick);
    }

    private static java.util.concurrent.Executor uiThread(Display display) {
        return task -> {
            if (!display.isDisposed()) {
                display.asyncExec(task);
            }
        };
    }

    private Chart chart(Composite parent, String title, String unit) {
        Chart c = new Chart(parent, SWT.NONE);
        c.setLayoutData(new GridData(SWT.FILL, SWT.FILL, true, true));
        c.getTitle().setText(title);
        c.getAxisSet().getXAxis(0).getTitle().setText("s (0: now)");
        c.getAxisSet().getYAxis(0).getTitle().setText(unit);
        return c;
    }

    private static void line(Chart chart, String name, int colour) {
        ILineSeries<?> s = (ILineSeries<?>) chart.getSeriesSet().createSeries(ISeries.SeriesType.LINE, name);
        s.setLineColor(chart.getDisplay().getSystemColor(colour));
        s.setSymbolType(ILineSeries.PlotSymbolType.NONE);
    }

    /** UI thread, every {@link #REFRESH_MS}: a snapshot of every robot into the table, the history and the plots. */
    private void tick() {
        if (table == null || table.getControl().isDisposed()) {
            return;
        }
        long t0 = System.nanoTime();
        refresh();
        slowestRefreshNanos = Math.max(slowestRefreshNanos, System.nanoTime() - t0);
        table.getControl().getDisplay().timerExec(REFRESH_MS, this::tick);
    }

    private void refresh() {
        FleetState fleet = binding.fleet();
        double now = (System.nanoTime() - startNanos) / 1e9;
        List<TrafficStatistics> snapshots = new ArrayList<>();
        Set<String> followed = new HashSet<>();
        if (fleet != null) {
            for (RobotState r : binding.robots()) {
                followed.add(r.jid());
                Optional<TrafficStatistics> s = fleet.traffic(r.jid());
                if (s.isPresent()) {
                    snapshots.add(s.get());
                    history.add(now, s.get());
                }
            }
        }
        for (TrafficStatistics old : rows) {
            if (!followed.contains(old.robot())) {
                history.remove(old.robot());
            }
        }
        rows = List.copyOf(snapshots);
        refreshes++;
        table.setInput(rows);
        if (selected == null && !rows.isEmpty()) {
            selected = rows.get(0).robot();
        }
        rows.stream().filter(s -> s.robot().equals(selected)).findFirst().ifPresent(s -> table.setSelection(
                new StructuredSelection(s)));
        summary.setText(fleet == null ? "no ControlML plug-in: nothing to count"
                : rows.isEmpty() ? "no robot followed on this connection (" + fleet.connection().summary() + ")"
                        : "the workbench's own traffic since it connected; rates over the last "
                                + TrafficStatistics.RATE_WINDOW_S + " s, round trips over the last "
                                + TrafficStatistics.ROUND_TRIP_WINDOW_S + " s" + (selected == null ? ""
                                        : "; plotted: " + selected));
        plot(now);
        askServer(fleet);
    }

    /** UI thread: asks for the selected robot's server figures when due; the answer comes back to the UI thread. */
    private void askServer(FleetState fleet) {
        long nanos = System.nanoTime();
        boolean robotChanged = selected != null && !selected.equals(serverAskedFor);
        if (fleet == null || selected == null || serverAsking || (!robotChanged && (serverHasNoArchive
                || nanos - serverAskedAt < SERVER_REFRESH_MS * 1_000_000L))) {
            return;
        }
        String robot = selected;
        serverAskedFor = robot;
        serverAskedAt = nanos;
        serverAsking = true;
        serverHasNoArchive = false;
        Display display = serverLine.getDisplay();
        fleet.serverStatistics(robot, SERVER_WINDOW).whenComplete((f, e) -> uiThread(display).execute(() -> {
            serverAsking = false;
            if (serverLine.isDisposed() || !robot.equals(selected)) {
                return;
            }
            Throwable why = e instanceof java.util.concurrent.CompletionException c && c.getCause() != null ? c
                    .getCause() : e;
            if (why instanceof FleetCommandException fe && fe.condition() == ControlMlCondition.UNSUPPORTED_OPERATION) {
                serverHasNoArchive = true;
            }
            String text = why instanceof FleetCommandException fe ? fe.getMessage() : String.valueOf(why);
            serverLine.setText(why == null ? TrafficTexts.server(f) : "server: " + text);
            serverLine.getParent().layout(true, false);
        }));
    }

    /** @return the line of the server's figures of the selected robot */
    public String serverLine() {
        return serverLine.getText();
    }

    private void plot(double now) {
        setSeries(messages, "in", selected == null ? null : history.series(selected, TrafficHistory.Series.IN, now));
        setSeries(messages, "out", selected == null ? null : history.series(selected, TrafficHistory.Series.OUT,
                now));
        setSeries(roundTrip, "p99", selected == null ? null : history.series(selected,
                TrafficHistory.Series.ROUND_TRIP_P99, now));
        for (Chart c : List.of(messages, roundTrip)) {
            c.getAxisSet().adjustRange();
            c.redraw();
        }
    }

    private static void setSeries(Chart chart, String name, double[][] xy) {
        ISeries<?> s = chart.getSeriesSet().getSeries(name);
        s.setXSeries(xy == null ? new double[0] : xy[0]);
        s.setYSeries(xy == null ? new double[0] : xy[1]);
    }

    private void select(String robot) {
        if (!robot.equals(selected)) {
            selected = robot;
            plot((System.nanoTime() - startNanos) / 1e9);
        }
    }

    private void selectionChanged(IWorkbenchPart part, ISelection selection) {
        if (part != this && selection instanceof IStructuredSelection s
                && s.getFirstElement() instanceof RobotState r) {
            select(r.jid());
        }
    }

    // ---- what the tests read (UI thread)

    /** @return the table's rows as shown, one snapshot per robot */
    public List<TrafficStatistics> rows() {
        return rows;
    }

    /** @return the cells of the table's row of a robot, by column title; empty when it has none */
    public Map<String, String> cells(String robot) {
        Map<String, String> m = new TreeMap<>();
        rows.stream().filter(s -> s.robot().equals(robot)).findFirst().ifPresent(s -> TrafficTexts.COLUMNS.forEach(
                c -> m.put(c.title(), c.text().apply(s))));
        return m;
    }

    /** @return the robot plotted, or null */
    public String selected() {
        return selected;
    }

    /** @return points of a plotted series: "in", "out" (stanzas/s) or "p99" (ms) */
    public int plotted(String series) {
        Chart c = series.equals("p99") ? roundTrip : messages;
        return c.getSeriesSet().getSeries(series).getYSeries().length;
    }

    /** @return refreshes so far */
    public long refreshes() {
        return refreshes;
    }

    /** @return the longest refresh so far on the UI thread, ns */
    public long slowestRefreshNanos() {
        return slowestRefreshNanos;
    }

    /** @return the view's area */
    public Composite content() {
        return table.getControl().getParent().getParent();
    }

    @Override
    public void setFocus() {
        table.getControl().setFocus();
    }

    @Override
    public void dispose() {
        getSite().getPage().removeSelectionListener(selectionListener);
        if (binding != null) {
            binding.dispose();
        }
        super.dispose();
    }
}
