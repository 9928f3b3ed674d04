package sabot.workbench.views;

import java.util.List;

import org.eclipse.jface.viewers.ArrayContentProvider;
import org.eclipse.jface.viewers.ColumnLabelProvider;
import org.eclipse.jface.viewers.TableViewer;
import org.eclipse.jface.viewers.TableViewerColumn;
import org.eclipse.swt.SWT;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Table;
import org.eclipse.ui.part.ViewPart;

/**
 * The fleet: one row per robot with its presence level, pose and current task. Rows come from the robots the
 * workbench's XMPP session knows; without a session the table is empty.
 */
public final class FleetView extends ViewPart {

    public static final String ID = "sabot.workbench.views.fleet";

    /** Column titles, in order. */
    public static final List<String> COLUMNS = List.of("Robot", "Presence", "Pose (x, y, θ)", "Task");
    private static final int[] WIDTHS = { 220, 110, 240, 300 };

    /**
     * One robot as the table shows it.
     *
     * @param robot    the robot's nickname or JID
     * @param presence Free, Busy, Away or Offline
     * @param pose     the last pose, formatted, or "–" when unknown
     * @param task     what the robot is doing
     */
    public record Row(String robot, String presence, String pose, String task) {
    }

    private TableViewer viewer;

    @Override
    public void createPartControl(Composite parent) {
        viewer = new TableViewer(parent, SWT.FULL_SELECTION | SWT.BORDER | SWT.V_SCROLL | SWT.H_SCROLL);
        Table table = viewer.getTable();
        table.setHeaderVisible(true);
        table.setLinesVisible(true);
        for (int i = 0; i < COLUMNS.size(); i++) {
            TableViewerColumn column = new TableViewerColumn(viewer, SWT.LEFT);
            column.getColumn().setText(COLUMNS.get(i));
            column.getColumn().setWidth(WIDTHS[i]);
            column.getColumn().setMoveable(true);
            int index = i;
            column.setLabelProvider(new ColumnLabelProvider() {
                @Override
                public String getText(Object element) {
                    Row r = (Row) element;
                    return switch (index) {
                        case 0 -> r.robot();
                        case 1 -> r.presence();
                        case 2 -> r.pose();
                        default -> r.task();
                    };
                }
            });
        }
        viewer.setContentProvider(ArrayContentProvider.getInstance());
        viewer.setInput(List.of());
    }

    /** Replaces the rows (UI thread only). */
    public void setRows(List<Row> rows) {
        viewer.setInput(List.copyOf(rows));
    }

    /** @return the table (for tests) */
    public Table table() {
        return viewer.getTable();
    }

    @Override
    public void setFocus() {
        viewer.getControl().setFocus();
    }
}
