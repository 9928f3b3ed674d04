package sabot.workbench.views;

import java.time.Duration;
import java.time.Instant;
import java.util.Comparator;
import java.util.List;
import java.util.Locale;
import java.util.function.Function;

import org.eclipse.jface.viewers.ArrayContentProvider;
import org.eclipse.jface.viewers.ColumnLabelProvider;
import org.eclipse.jface.viewers.ISelection;
import org.eclipse.jface.viewers.IStructuredSelection;
import org.eclipse.jface.viewers.StructuredSelection;
import org.eclipse.jface.viewers.TableViewer;
import org.eclipse.jface.viewers.TableViewerColumn;
import org.eclipse.jface.viewers.Viewer;
import org.eclipse.jface.viewers.ViewerComparator;
import org.eclipse.jface.viewers.ViewerFilter;
import org.eclipse.jface.layout.GridDataFactory;
import org.eclipse.jface.layout.GridLayoutFactory;
import org.eclipse.swt.SWT;
import org.eclipse.swt.graphics.Color;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Table;
import org.eclipse.swt.widgets.TableColumn;
import org.eclipse.swt.widgets.Text;
import org.eclipse.ui.ISelectionListener;
import org.eclipse.ui.IWorkbenchPart;
import org.eclipse.ui.contexts.IContextService;
import org.eclipse.ui.part.ViewPart;

import sabot.controlml.payload.MissionStatus;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.fleet.FleetBinding;

/**
 * The fleet: one live row per robot of the {@link sabot.workbench.fleet.FleetState} with its presence level and
 * reason, pose, mission state and progress, and the age of its last telemetry; stale rows are grey. Click a header to
 * sort by it (again to reverse); the selection is the workbench's (the workspace map follows it); double-click centres
 * the map on the robot. The filter field above the table keeps the rows whose robot name or JID, presence (level and
 * reason) or mission (state, progress, detail) contains the typed text, ignoring case, as Eclipse's own views filter.
 */
public final class FleetView extends ViewPart {

    public static final String ID = "sabot.workbench.views.fleet";

    /** Column titles, in order. */
    public static final List<String> COLUMNS = List.of("Robot", "Presence", "Pose (x, y, θ)", "Mission",
            "Telemetry");
    private static final int[] WIDTHS = { 220, 220, 220, 330, 110 };
    /** How often the ages are refreshed without news (ms): stale robots turn grey without an event. */
    private static final int AGE_REFRESH_MS = 500;

    /** Hint shown in the empty filter field. */
    public static final String FILTER_HINT = "Filter: robot, presence or mission";

    private TableViewer viewer;
    private Text filter;
    private String filterText = "";
    private FleetBinding fleet;
    private int sortColumn = 0;
    private boolean descending;
    private Color grey;
    private final ISelectionListener otherViews = this::otherViewSelected;

    /** The texts of one row (for tests and the sort). */
    public static List<String> texts(RobotState r, Instant now) {
        return List.of(r.name() + " <" + r.jid() + ">", presence(r), pose(r), mission(r.mission()), age(r, now));
    }

    private static String presence(RobotState r) {
        return r.reason().isEmpty() ? r.availability().label() : r.availability().label() + " — " + r.reason();
    }

    private static String pose(RobotState r) {
        return r.pose() == null ? "–" : String.format(Locale.ROOT, "%.2f m, %.2f m, %.1f°", r.pose().pose().x(), r
                .pose().pose().y(), Math.toDegrees(r.pose().pose().theta()));
    }

    private static String mission(MissionStatus m) {
        if (m == null) {
            return "–";
        }
        String s = String.format(Locale.ROOT, "%s %.0f %%", m.state().code(), m.progress());
        return (m.maintenance() ? "maintenance, " : "") + (m.detail().isEmpty() ? s : s + " — " + m.detail());
    }

    private static String age(RobotState r, Instant now) {
        Duration d = r.telemetryAge(now);
        if (d == null) {
            return "never";
        }
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
                public String getText(Object element) {
                    return texts((RobotState) element, Instant.now()).get(index);
                }

                @Override
                public Color getForeground(Object element) {
                    return ((RobotState) element).isStale(Instant.now()) ? grey : null;
                }
            });
        }
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
        viewer.setInput(List.of());
        viewer.addDoubleClickListener(e -> {
            if (e.getSelection() instanceof IStructuredSelection s && s.getFirstElement() instanceof RobotState r) {
                WorkspaceView map = (WorkspaceView) getSite().getPage().findView(WorkspaceView.ID);
                if (map != null) {
                    map.select(r.jid(), true);
                    map.centreOn(r.jid());
                }
            }
        });
        getSite().setSelectionProvider(viewer);
        getSite().getService(IContextService.class).activateContext(WorkspaceView.FLEET_CONTEXT);
        getSite().getPage().addSelectionListener(otherViews);
        fleet = new FleetBinding(table.getDisplay()::asyncExec, this::refresh);
        tick();
    }

    private static Comparator<RobotState> comparator(int column) {
        Function<RobotState, Comparable<?>> key = switch (column) {
            case 1 -> r -> r.availability().ordinal() * 1000 + 0;
            case 2 -> r -> r.pose() == null ? Double.NEGATIVE_INFINITY : r.pose().pose().x();
            case 3 -> r -> r.mission() == null ? -1.0 : r.mission().progress();
            case 4 -> r -> r.lastTelemetry() == null ? Instant.MIN : r.lastTelemetry();
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
    }

    private void tick() {
        if (viewer.getTable().isDisposed()) {
            return;
        }
        viewer.refresh(true);
        viewer.getTable().getDisplay().timerExec(AGE_REFRESH_MS, this::tick);
    }

    private void refresh() {
        if (viewer.getTable().isDisposed()) {
            return;
        }
        ISelection before = viewer.getSelection();
        String selected = before instanceof IStructuredSelection s && s.getFirstElement() instanceof RobotState r ? r
                .jid() : null;
        List<RobotState> robots = fleet.robots();
        viewer.setInput(robots);
        if (selected != null) {
            robots.stream().filter(r -> r.jid().equals(selected)).findFirst().ifPresent(r -> viewer.setSelection(
                    new StructuredSelection(r)));
        }
    }

    private void otherViewSelected(IWorkbenchPart part, ISelection selection) {
        if (part == this || !(selection instanceof IStructuredSelection s)) {
            return;
        }
        if (s.getFirstElement() instanceof RobotState r) {
            fleet.robots().stream().filter(x -> x.jid().equals(r.jid())).findFirst().ifPresent(x -> viewer
                    .setSelection(new StructuredSelection(x), true));
        }
    }

    /** @return the table (for tests) */
    public Table table() {
        return viewer.getTable();
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
