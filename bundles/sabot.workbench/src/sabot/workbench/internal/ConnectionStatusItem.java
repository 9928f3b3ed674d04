package sabot.workbench.internal;

import org.eclipse.jface.action.ContributionItem;
import org.eclipse.jface.action.StatusLineLayoutData;
import org.eclipse.swt.SWT;
import org.eclipse.swt.custom.CLabel;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Label;

import sabot.workbench.fleet.ConnectionStatus;
import sabot.workbench.fleet.FleetBinding;

/** The status line's connection state: the account and whether it is online, connecting or retrying (and why). */
final class ConnectionStatusItem extends ContributionItem {

    static final String ID = "sabot.workbench.status.connection";
    /** Shown while no ControlML plug-in provides a fleet. */
    static final String NO_FLEET = "no fleet (ControlML plug-in not installed)";

    private CLabel label;
    private FleetBinding fleet;

    ConnectionStatusItem() {
        super(ID);
    }

    @Override
    public void fill(Composite parent) {
        Label separator = new Label(parent, SWT.SEPARATOR);
        label = new CLabel(parent, SWT.SHADOW_NONE);
        label.setLayoutData(new StatusLineLayoutData() {
            {
                widthHint = 560;
            }
        });
        StatusLineLayoutData line = new StatusLineLayoutData();
        line.heightHint = 20;
        separator.setLayoutData(line);
        fleet = new FleetBinding(parent.getDisplay()::asyncExec, this::refresh);
        label.addDisposeListener(e -> fleet.dispose());
        refresh();
    }

    private void refresh() {
        if (label == null || label.isDisposed()) {
            return;
        }
        ConnectionStatus s = fleet.status();
        String text = s == null ? NO_FLEET : s.summary();
        label.setText(text);
        label.setToolTipText(text);
    }

    /** @return the text shown (for tests) */
    String text() {
        return label == null ? null : label.getText();
    }
}
