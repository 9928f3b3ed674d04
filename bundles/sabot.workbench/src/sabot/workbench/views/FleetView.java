package sabot.workbench.views;

import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.HashSet;
import java.util.Comparator;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.TimeUnit;
import java.util.function.Function;

import org.eclipse.jface.action.Action;
import org.eclipse.jface.action.MenuManager;
import org.eclipse.jface.viewers.ArrayContentProvider;
import org.eclipse.jface.viewers.ColumnLabelProvider;
import org.eclipse.jface.viewers.IElementComparer;
import org.eclipse.jface.viewers.ISelection;
import org.eclipse.jface.viewers.IStructuredSelection;
import org.eclipse.jface.viewers.StructuredSelection;
import org.eclipse.jface.viewers.TableViewer;
import org.eclipse.jface.viewers.TableViewerColumn;
import org.eclipse.jface.viewers.Viewer;
import org.eclipse.jface.viewers.ViewerComparator;
import org.eclipse.jface.viewers.ViewerCell;
import org.eclipse.jface.viewers.ViewerFilter;
import org.eclipse.jface.layout.GridDataFactory;
import org.eclipse.jface.layout.GridLayoutFactory;
import org.eclipse.swt.SWT;
import org.eclipse.swt.graphics.Color;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Table;
import org.eclipse.swt.widgets.TableColumn;
import org.eclipse.swt.widgets.TableItem;
import org.eclipse.swt.widgets.Text;
import org.eclipse.ui.ISelectionListener;
import org.eclipse.ui.IWorkbenchPart;
import org.eclipse.ui.contexts.IContextService;
import org.eclipse.ui.part.ViewPart;

import sabot.controlml.payload.MissionStatus;
import sabot.model.robot.BatteryState;
import sabot.workbench.fleet.FleetBinding;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.QueuedCommand;
import sabot.workbench.fleet.RobotState;

/**
 * The fleet: one live row per robot of the {@link sabot.workbench.fleet.FleetState} with its presence level and
 * reason, pose, mission state and progress (for a mission of several targets the target it is on and the missions
 * queued, {@link #mission}), and the age of its last telemetry (with how late its poses arrive when
 * they lag, {@link RobotState#isLate()}); stale rows are grey. Click a header to
 * sort by it (again to reverse); the selection is the workbench's (the workspace map follows it); double-click centres
 * the map on the robot. The filter field above the table keeps the rows whose robot name or JID, presence (level and
 * reason) or mission (state, progress, detail) contains the typed text, ignoring case, as Eclipse's own views filter.
 * <p>
 * Telemetry reaches the rows at most every {@value #UPDATE_MS} ms, and then only the rows whose robot changed: a
 * hundred robots at 10 Hz come as dozens of bursts a second, and rewriting every row on each took about a quarter of
 * the UI thread (the map, not the table, is where the operator watches motion). A robot added or removed, or a change
 * of presence, is shown at once. The telemetry ages are refreshed every {@value #AGE_REFRESH_MS} ms on their own.
 * <p>
 * The context menu opens a robot's command history from the server's archive ({@link CommandHistoryDialog}).
 * <p>
 * Below the table, while any asks, the robots asking for access (enrolled by the lab, not yet approved: not in the
 * fleet) with their identity ({@link AccessRequests}).
 */
public final class FleetView extends ViewPart {

    public static final String ID = "sabot.workbench.views.fleet";

    /** Column titles, in order. */
    public static final List<String> COLUMNS = List.of("Robot", "Presence", "Pose (x, y, θ)", "Mission",
            "Telemetry", "Battery");
    private static final int[] WIDTHS = { 200, 200, 180, 310, 100, 190 };
    /** How often the ages are refreshed without news (ms): stale robots turn grey without an event. */
    static final int AGE_REFRESH_MS = 500;
    /**
     * Least time between two updates of the rows by telemetry (ms): four a second reads as live in a table, and the
     * rows' cost no longer grows with the telemetry rate.
     */
    public static final int UPDATE_MS = 250;
    private static final int AGE_COLUMN = 4;

    /** The tooltip of the robots asking for access: what the request means and where it is answered. */
    public static final String ACCESS_REQUESTS_TOOLTIP = "Robots enrolled by the lab and not yet approved: they obey "
            + "nobody. Approve or refuse one on the lab's XMPP server: ./sabot enrol approve JID, ./sabot enrol refuse "
            + "JID";

    /** The context menu's item that opens a robot's command history. */
    public static final String COMMAND_HISTORY = "Command History…";

    /** Hint shown in the empty filter field. */
    public static final String FILTER_HINT = "Filter: robot, presence or mission";

    private TableViewer viewer;
    private Text filter;
    private String filterText = "";
    private FleetBinding fleet;
    /** The commands waiting for offline robots that the rows show (UI thread only). */
    private List<QueuedCommand> shownQueued = List.of();
    /** The robots asking for access, below the table (hidden while none asks). */
    private AccessRequests accessRequests;
    private int sortColumn = 0;
    private boolean descending;
    private Color grey;
    private final ISelectionListener otherViews = this::otherViewSelected;
    /** The robots the rows show, by JID (the viewer's input; UI thread only). */
    private final Map<String, RobotState> model = new LinkedHashMap<>();
    /** An update of the rows is due by the timer (UI thread only). */
    private boolean updateScheduled;
    private final Runnable scheduledUpdate = () -> {
        updateScheduled = false;
        update();
    };
    /** {@link System#nanoTime()} of the last update of the rows. */
    private long lastUpdateNanos;
    /** Rows (re)written with the label providers since the view opened. */
    private long rowsWritten;

    /** The texts of one row (for tests and the sort). */
    public static List<String> texts(RobotState r, Instant now) {
        return texts(r, now, List.of());
    }

    /**
     * The texts of one row, with the commands waiting for the robot while it is offline
     * ({@link sabot.workbench.fleet.FleetState#queuedCommands()}; those of other robots are ignored) in its Mission
     * column.
     */
    public static List<String> texts(RobotState r, Instant now, List<QueuedCommand> queued) {
        String mission = mission(r.mission());
        List<String> waiting = queued.stream().filter(q -> q.robot().equals(r.jid())).map(q -> q.what() + " (sent "
                + seconds(Duration.between(q.queuedAt(), now)) + " ago)").toList();
        if (!waiting.isEmpty()) {
            mission = "queued until online: " + String.join("; ", waiting) + (r.mission() == null ? "" : " | "
                    + mission);
        }
        return List.of(r.name() + " <" + r.jid() + ">", presence(r), pose(r), mission, age(r, now), battery(r
                .battery()));
    }

    /**
     * @return a battery for its column: {@code 87 % · 25.31 V}, with {@code · charging}, {@code · full} or
     *         {@code · docked}; {@code –} before the first reading
     */
    static String battery(BatteryState b) {
        if (b == null) {
            return "–";
        }
        return String.format(Locale.ROOT, "%.0f %% · %.2f V%s", b.stateOfCharge() * 100, b.voltage(), b.charging()
                ? " · charging" : b.full() ? " · full" : b.docked() ? " · docked" : "");
    }

    private static String presence(RobotState r) {
        return r.reason().isEmpty() ? r.availability().label() : r.availability().label() + " — " + r.reason();
    }

    private static String pose(RobotState r) {
        return r.pose() == null ? "–" : String.format(Locale.ROOT, "%.2f m, %.2f m, %.1f°", r.pose().pose().x(), r
                .pose().pose().y(), Math.toDegrees(r.pose().pose().theta()));
    }

    /**
     * @return a mission for its column: {@code running 40 %}, and for a mission of several targets the one the robot
     *         is on ({@code running · target 2/4 · 37 %}, once all are reached {@code done · 4/4 targets · 100 %}), the
     *         missions queued after it ({@code · 1 queued}), then the detail
     */
    static String mission(MissionStatus m) {
        if (m == null) {
            return "–";
        }
        String s;
        int count = m.targets().size();
        if (count == 0) {
            s = String.format(Locale.ROOT, "%s %.0f %%", m.state().code(), m.progress());
        } else {
            String target = m.current() < count ? "target " + (m.current() + 1) + "/" + count : count + "/" + count
                    + " targets";
            s = String.format(Locale.ROOT, "%s · %s · %.0f %%", m.state().code(), target, m.progress());
        }
        if (m.queued() > 0) {
            s += " · " + m.queued() + " queued";
        }
        return (m.maintenance() ? "maintenance, " : "") + (m.detail().isEmpty() ? s : s + " — " + m.detail());
    }

    private static String age(RobotState r, Instant now) {
        Duration d = r.telemetryAge(now);
        if (d == null) {
            return "never";
        }
        String age = seconds(d);
        // poses that keep coming, but late: the lag over the robot's fastest pose (RobotState.isLate)
        return r.isLate() ? age + ", " + seconds(r.poseLag().lag()) + " late" : age;
    }

    private static String seconds(Duration d) {
        long ms = Math.max(0, d.toMillis());
        return ms < 10_000 ? String.format(Locale.ROOT, "%.1f s", ms / 1000.0) : ms / 1000 + " s";
    }

    /**
     * @return true when a row matches the filter text: its robot (name and JID), presence or mission column contains
     *         {@code text}, ignoring case; a blank text matches every row
     */
    public static boolean matches(RobotState r, String text) {
        String needle = text == null ? "" : text.strip().toLowerCase(Locale.ROOT);
        if (needle.isEmpty()) {
            return true;
        }
        List<String> t = texts(r, Instant.now());
        return t.get(0).toLowerCase(Locale.ROOT).contains(needle) || t.get(1).toLowerCase(Locale.ROOT).contains(needle)
                || t.get(3).toLowerCase(Locale.ROOT).contains(needle);
    }

    @Override
    public void createPartControl(Composite parent) {
        parent.setLayout(GridLayoutFactory.fillDefaults().spacing(0, 2).create());
        filter = new Text(parent, SWT.SEARCH | SWT.ICON_SEARCH | SWT.ICON_CANCEL | SWT.BORDER);
        filter.setMessage(FILTER_HINT);
        GridDataFactory.fillDefaults().grab(true, false).applyTo(filter);
        filter.addModifyListener(e -> setFilter(filter.getText()));
        filter.addListener(SWT.DefaultSelection, e -> {
            if (e.detail == SWT.ICON_CANCEL) {
                filter.setText("");
            }
        });
        viewer = new TableViewer(parent, SWT.FULL_SELECTION | SWT.BORDER | SWT.V_SCROLL | SWT.H_SCROLL);
        Table table = viewer.getTable();
        GridDataFactory.fillDefaults().grab(true, true).applyTo(table);
        table.setHeaderVisible(true);
        table.setLinesVisible(true);
        grey = new Color(150, 150, 150);
        table.addDisposeListener(e -> grey.dispose());
        for (int i = 0; i < COLUMNS.size(); i++) {
            TableViewerColumn column = new TableViewerColumn(viewer, SWT.LEFT);
            TableColumn c = column.getColumn();
            c.setText(COLUMNS.get(i));
            c.setWidth(WIDTHS[i]);
            c.setMoveable(true);
            int index = i;
            c.addListener(SWT.Selection, e -> sortBy(index));
            column.setLabelProvider(new ColumnLabelProvider() {
                @Override
                public void update(ViewerCell cell) {
                    if (index == 0) {
                        rowsWritten++;
                    }
                    super.update(cell);
                }

                @Override
                public String getText(Object element) {
                    return texts((RobotState) element, Instant.now(), fleet.queuedCommands()).get(index);
                }

                @Override
                public Color getForeground(Object element) {
                    return ((RobotState) element).isStale(Instant.now()) ? grey : null;
                }
            });
        }
        // rows are robots by JID: a new state of a robot is the same row (and keeps the selection)
        viewer.setComparer(new IElementComparer() {
            @Override
            public boolean equals(Object a, Object b) {
                return a instanceof RobotState x && b instanceof RobotState y ? x.jid().equals(y.jid()) : a.equals(b);
            }

            @Override
            public int hashCode(Object element) {
                return element instanceof RobotState r ? r.jid().hashCode() : element.hashCode();
            }
        });
        viewer.setUseHashlookup(true);
        accessRequests = new AccessRequests(parent);
        viewer.setContentProvider(ArrayContentProvider.getInstance());
        viewer.setComparator(new ViewerComparator() {
            @Override
            public int compare(Viewer v, Object a, Object b) {
                int c = comparator(sortColumn).compare((RobotState) a, (RobotState) b);
                return descending ? -c : c;
            }
        });
        viewer.setFilters(new ViewerFilter() {
            @Override
            public boolean select(Viewer v, Object parentElement, Object element) {
                return matches((RobotState) element, filterText);
            }
        });
        viewer.setInput(model.values());
        viewer.addDoubleClickListener(e -> {
            if (e.getSelection() instanceof IStructuredSelection s && s.getFirstElement() instanceof RobotState r) {
                WorkspaceView map = (WorkspaceView) getSite().getPage().findView(WorkspaceView.ID);
                if (map != null) {
                    map.select(r.jid(), true);
                    map.centreOn(r.jid());
                }
            }
        });
        MenuManager menu = new MenuManager();
        menu.setRemoveAllWhenShown(true);
        menu.addMenuListener(m -> {
            RobotState r = viewer.getStructuredSelection().getFirstElement() instanceof RobotState s ? s : null;
            Action history = new Action(COMMAND_HISTORY) {
                @Override
                public void run() {
                    openCommandHistory(r.jid());
                }
            };
            history.setEnabled(r != null && fleet.fleet() != null);
            m.add(history);
        });
        table.setMenu(menu.createContextMenu(table));
        getSite().setSelectionProvider(viewer);
        getSite().getService(IContextService.class).activateContext(WorkspaceView.FLEET_CONTEXT);
        getSite().getPage().addSelectionListener(otherViews);
        fleet = new FleetBinding(table.getDisplay()::asyncExec, this::fleetChanged);
        table.getVerticalBar().addListener(SWT.Selection, e -> watchVisibleRows());
        table.addListener(SWT.Resize, e -> watchVisibleRows());
        tick();
    }

    /**
     * Leases the telemetry of the robots in the table's visible rows at {@link FleetState#LISTED_HZ} (docs/CONTROLML.md
     * section 6, "Leases"): a list of a thousand robots costs the rows an operator sees. Called when the rows or the
     * scroll position change.
     */
    private void watchVisibleRows() {
        Table t = viewer.getTable();
        if (t.isDisposed() || fleet == null) {
            return;
        }
        int top = t.getTopIndex();
        int rows = t.getClientArea().height / Math.max(1, t.getItemHeight()) + 1; // a row partly shown counts
        Set<String> shown = new HashSet<>();
        for (int i = top; i < Math.min(t.getItemCount(), top + rows); i++) {
            if (t.getItem(i).getData() instanceof RobotState r) {
                shown.add(r.jid());
            }
        }
        fleet.watch(shown, FleetState.LISTED_HZ);
    }

    /** @return the fleet the view shows, or null while none is there */
    public FleetState fleetState() {
        return fleet.fleet();
    }

    /**
     * Opens a robot's command history from the server's archive ({@link CommandHistoryDialog}), as the context menu's
     * item does.
     *
     * @return the dialog, open (it reads the history in the background); null when no fleet is there to ask
     */
    public CommandHistoryDialog openCommandHistory(String jid) {
        FleetState state = fleet.fleet();
        if (state == null) {
            return null;
        }
        CommandHistoryDialog dialog = new CommandHistoryDialog(getSite().getShell(), state, jid);
        dialog.open();
        return dialog;
    }

    private static Comparator<RobotState> comparator(int column) {
        Function<RobotState, Comparable<?>> key = switch (column) {
            case 1 -> r -> r.availability().ordinal() * 1000 + 0;
            case 2 -> r -> r.pose() == null ? Double.NEGATIVE_INFINITY : r.pose().pose().x();
            case 3 -> r -> r.mission() == null ? -1.0 : r.mission().progress();
            case 4 -> r -> r.lastTelemetry() == null ? Instant.MIN : r.lastTelemetry();
            case 5 -> r -> r.battery() == null ? -1.0 : r.battery().stateOfCharge();
            default -> RobotState::name;
        };
        @SuppressWarnings({ "unchecked", "rawtypes" })
        Comparator<RobotState> c = Comparator.comparing(r -> (Comparable) key.apply(r));
        return c.thenComparing(RobotState::jid);
    }

    /**
     * Filters the rows (as typing into the filter field does); the field shows the text.
     *
     * @param text the text the rows must contain; blank shows every row
     */
    public void setFilter(String text) {
        String t = text == null ? "" : text;
        if (!filter.getText().equals(t)) {
            filter.setText(t); // comes back here through the modify listener
            return;
        }
        if (!t.equals(filterText)) {
            filterText = t;
            viewer.refresh();
            watchVisibleRows();
        }
    }

    /** @return the filter field (for tests) */
    public Text filterField() {
        return filter;
    }

    /** Sorts by a column; the same column again reverses the order. */
    public void sortBy(int column) {
        descending = column == sortColumn && !descending;
        sortColumn = column;
        Table t = viewer.getTable();
        t.setSortColumn(t.getColumn(column));
        t.setSortDirection(descending ? SWT.DOWN : SWT.UP);
        viewer.refresh();
        watchVisibleRows();
    }

    /** Refreshes the ages and the greying of stale robots: one cell a row, without the label providers. */
    private void tick() {
        Table table = viewer.getTable();
        if (table.isDisposed()) {
            return;
        }
        Instant now = Instant.now();
        for (TableItem item : table.getItems()) {
            if (item.getData() instanceof RobotState r) {
                item.setText(AGE_COLUMN, age(r, now));
                item.setForeground(r.isStale(now) ? grey : null);
            }
        }
        table.getDisplay().timerExec(AGE_REFRESH_MS, this::tick);
    }

    /** The fleet changed (once per burst of changes): the rows follow at once or within {@link #UPDATE_MS}. */
    private void fleetChanged() {
        if (viewer.getTable().isDisposed()) {
            return;
        }
        accessRequests.show(fleet.accessRequests(), fleet.fleet());
        List<QueuedCommand> queued = fleet.queuedCommands();
        if (!queued.equals(shownQueued)) {
            shownQueued = queued; // rows whose robots' states did not change show them too
            viewer.refresh();
            watchVisibleRows();
        }
        List<RobotState> robots = fleet.robots();
        if (presenceOrMembershipChanged(robots)) {
            update();
            return;
        }
        if (!updateScheduled) {
            updateScheduled = true;
            long due = lastUpdateNanos + TimeUnit.MILLISECONDS.toNanos(UPDATE_MS) - System.nanoTime();
            int delayMs = (int) Math.max(0, TimeUnit.NANOSECONDS.toMillis(due));
            if (delayMs == 0) {
                viewer.getTable().getDisplay().asyncExec(scheduledUpdate);
            } else {
                viewer.getTable().getDisplay().timerExec(delayMs, scheduledUpdate);
            }
        }
    }

    /** @return true when a robot came or went or its presence (level or reason) is not the one shown */
    private boolean presenceOrMembershipChanged(List<RobotState> robots) {
        if (robots.size() != model.size()) {
            return true;
        }
        for (RobotState r : robots) {
            RobotState shown = model.get(r.jid());
            if (shown == null || shown.availability() != r.availability() || !shown.reason().equals(r.reason())) {
                return true;
            }
        }
        return false;
    }

    /** Brings the rows to the fleet's state: the changed rows alone while the rows' order and set stay. */
    private void update() {
        if (viewer.getTable().isDisposed()) {
            return;
        }
        if (updateScheduled) {
            viewer.getTable().getDisplay().timerExec(-1, scheduledUpdate);
            updateScheduled = false;
        }
        lastUpdateNanos = System.nanoTime();
        List<RobotState> robots = fleet.robots();
        boolean sameRobots = robots.size() == model.size();
        List<RobotState> changed = new ArrayList<>();
        for (RobotState r : robots) {
            RobotState shown = model.get(r.jid());
            sameRobots &= shown != null;
            if (shown != r) {
                changed.add(r);
            }
        }
        model.clear();
        robots.forEach(r -> model.put(r.jid(), r));
        if (changed.isEmpty() && sameRobots) {
            return;
        }
        if (sameRobots && sameRowOrder()) {
            viewer.update(changed.toArray(), null);
        } else {
            viewer.refresh(); // keeps the selection (the comparer knows robots by JID)
            watchVisibleRows();
        }
    }

    /** @return true when the rows' robots, filtered and sorted anew with their latest states, are those shown */
    private boolean sameRowOrder() {
        TableItem[] items = viewer.getTable().getItems();
        Object[] rows = model.values().stream().filter(r -> matches(r, filterText)).toArray();
        if (rows.length != items.length) {
            return false;
        }
        viewer.getComparator().sort(viewer, rows);
        for (int i = 0; i < rows.length; i++) {
            if (!(items[i].getData() instanceof RobotState shown) || !shown.jid().equals(((RobotState) rows[i])
                    .jid())) {
                return false;
            }
        }
        return true;
    }

    /** @return how many rows were written with the label providers since the view opened (for tests and figures) */
    public long rowsWritten() {
        return rowsWritten;
    }

    private void otherViewSelected(IWorkbenchPart part, ISelection selection) {
        if (part == this || !(selection instanceof IStructuredSelection s)) {
            return;
        }
        if (s.getFirstElement() instanceof RobotState r && model.containsKey(r.jid())) {
            viewer.setSelection(new StructuredSelection(model.get(r.jid())), true);
        }
    }

    /** @return the table (for tests) */
    public Table table() {
        return viewer.getTable();
    }

    /**
     * @return the robots asking for access as the section below the table shows them: per row who asks (nickname and
     *         JID) and its UUID (for tests)
     */
    public List<List<String>> accessRequestRows() {
        return accessRequests.rowTexts();
    }

    /** @return the section of the robots asking for access (for tests and screenshots) */
    public Table accessRequestTable() {
        return accessRequests.table();
    }

    /** @return the rows in the table's order (for tests) */
    public List<RobotState> rows() {
        return java.util.Arrays.stream(viewer.getTable().getItems()).map(i -> (RobotState) i.getData()).toList();
    }

    @Override
    public void setFocus() {
        viewer.getControl().setFocus();
    }

    @Override
    public void dispose() {
        getSite().getPage().removeSelectionListener(otherViews);
        if (fleet != null) {
            fleet.dispose();
        }
        super.dispose();
    }
}
