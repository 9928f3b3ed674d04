package sabot.workbench.views;

import java.time.Duration;
import java.time.ZoneId;
import java.time.format.DateTimeFormatter;
import java.util.List;
import java.util.Locale;
import java.util.Objects;
import java.util.concurrent.CompletableFuture;

import org.eclipse.jface.dialogs.Dialog;
import org.eclipse.jface.dialogs.IDialogConstants;
import org.eclipse.jface.layout.GridDataFactory;
import org.eclipse.jface.viewers.ArrayContentProvider;
import org.eclipse.jface.viewers.ColumnLabelProvider;
import org.eclipse.jface.viewers.TableViewer;
import org.eclipse.jface.viewers.TableViewerColumn;
import org.eclipse.swt.SWT;
import org.eclipse.swt.layout.GridLayout;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Control;
import org.eclipse.swt.widgets.Label;
import org.eclipse.swt.widgets.Shell;
import org.eclipse.swt.widgets.Table;

import sabot.fleet.ArchivedCommand;
import sabot.workbench.fleet.FleetCommandException;
import sabot.workbench.fleet.FleetState;

/**
 * A robot's latest commands as the lab's server archived them (docs/ARCHIVE.md, {@link FleetState#commandHistory}):
 * when, from whom, which resource, and the robot's answer (with an error's condition and text), newest first. Opened
 * from the Fleet view's context menu; read once when it opens, again with Refresh.
 */
public final class CommandHistoryDialog extends Dialog {

    /** How many commands are read (the newest). */
    public static final int MAX = 200;
    /** Column titles, in order. */
    public static final List<String> COLUMNS = List.of("Time", "From", "Resource", "Answer", "In", "Why");
    private static final int[] WIDTHS = { 170, 310, 110, 70, 70, 330 };
    private static final int REFRESH_ID = IDialogConstants.CLIENT_ID + 1;
    private static final DateTimeFormatter TIME = DateTimeFormatter.ofPattern("yyyy-MM-dd HH:mm:ss.SSS", Locale.ROOT)
            .withZone(ZoneId.systemDefault());

    private final FleetState fleet;
    private final String robot;
    private TableViewer viewer;
    private Label status;
    private List<ArchivedCommand> shown = List.of();
    private String statusText = "";

    /**
     * @param parent the shell it belongs to
     * @param fleet  the fleet it reads from
     * @param robot  the robot's bare JID
     */
    public CommandHistoryDialog(Shell parent, FleetState fleet, String robot) {
        super(parent);
        this.fleet = Objects.requireNonNull(fleet, "fleet");
        this.robot = Objects.requireNonNull(robot, "robot");
        setShellStyle(getShellStyle() | SWT.RESIZE | SWT.MODELESS);
        setBlockOnOpen(false);
    }

    /** The texts of one row (for tests). */
    public static List<String> texts(ArchivedCommand c) {
        Duration in = c.answerIn();
        String why = c.condition().isEmpty() ? c.text() : c.text().isEmpty() ? c.condition() : c.condition() + ": "
                + c.text();
        return List.of(TIME.format(c.at()), c.from(), c.resource() + (c.stored() ? " (stored)" : ""), c.answer()
                .isEmpty() ? "none" : c.answer(), in == null ? "" : String.format(Locale.ROOT, "%.1f ms", in.toNanos()
                        / 1e6), why);
    }

    @Override
    protected void configureShell(Shell shell) {
        super.configureShell(shell);
        shell.setText("Command History of " + robot);
    }

    @Override
    protected Control createDialogArea(Composite parent) {
        Composite area = (Composite) super.createDialogArea(parent);
        area.setLayout(new GridLayout(1, false));
        status = new Label(area, SWT.WRAP);
        GridDataFactory.fillDefaults().grab(true, false).applyTo(status);
        viewer = new TableViewer(area, SWT.BORDER | SWT.FULL_SELECTION | SWT.V_SCROLL | SWT.H_SCROLL);
        Table table = viewer.getTable();
        table.setHeaderVisible(true);
        table.setLinesVisible(true);
        GridDataFactory.fillDefaults().grab(true, true).hint(1100, 360).applyTo(table);
        for (int i = 0; i < COLUMNS.size(); i++) {
            int index = i;
            TableViewerColumn column = new TableViewerColumn(viewer, SWT.LEFT);
            column.getColumn().setText(COLUMNS.get(i));
            column.getColumn().setWidth(WIDTHS[i]);
            column.setLabelProvider(new ColumnLabelProvider() {
                @Override
                public String getText(Object element) {
                    return texts((ArchivedCommand) element).get(index);
                }
            });
        }
        viewer.setContentProvider(ArrayContentProvider.getInstance());
        read();
        return area;
    }

    @Override
    protected void createButtonsForButtonBar(Composite parent) {
        createButton(parent, REFRESH_ID, "Refresh", false);
        createButton(parent, IDialogConstants.CLOSE_ID, IDialogConstants.CLOSE_LABEL, true);
    }

    @Override
    protected void buttonPressed(int buttonId) {
        if (buttonId == REFRESH_ID) {
            read();
        } else if (buttonId == IDialogConstants.CLOSE_ID) {
            close();
        } else {
            super.buttonPressed(buttonId);
        }
    }

    /** Reads the history again; the rows and the status line change when the answer comes. */
    public void read() {
        show(shown, "Reading the archive of " + robot + "…");
        CompletableFuture<List<ArchivedCommand>> answer = fleet.commandHistory(robot, MAX);
        answer.whenComplete((commands, failure) -> {
            if (status.isDisposed()) {
                return;
            }
            status.getDisplay().asyncExec(() -> {
                if (status.isDisposed()) {
                    return;
                }
                if (failure != null) {
                    FleetCommandException f = FleetCommandException.in(failure);
                    show(List.of(), "No command history: " + (f != null ? f.text() : failure.toString()));
                } else {
                    show(commands, commands.isEmpty() ? "No command archived for " + robot
                            : commands.size() + " command(s), newest first" + (commands.size() == MAX ? " (the "
                                    + MAX + " newest)" : ""));
                }
            });
        });
    }

    private void show(List<ArchivedCommand> commands, String text) {
        shown = List.copyOf(commands);
        statusText = text;
        status.setText(text);
        viewer.setInput(shown);
        status.getParent().layout(true);
    }

    /** @return the commands shown (UI thread) */
    public List<ArchivedCommand> shown() {
        return shown;
    }

    /** @return the status line: reading, how many, or why there is no history (UI thread) */
    public String statusText() {
        return statusText;
    }
}
