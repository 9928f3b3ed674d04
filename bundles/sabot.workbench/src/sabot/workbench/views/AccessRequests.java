package sabot.workbench.views;

import java.io.ByteArrayInputStream;
import java.util.HashMap;
import java.util.List;
import java.util.Map;

import org.eclipse.jface.layout.GridDataFactory;
import org.eclipse.swt.SWT;
import org.eclipse.swt.SWTException;
import org.eclipse.swt.graphics.Image;
import org.eclipse.swt.graphics.ImageData;
import org.eclipse.swt.layout.GridData;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Table;
import org.eclipse.swt.widgets.TableColumn;
import org.eclipse.swt.widgets.TableItem;

import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotIdentity;

/**
 * The Fleet view's list of the robots asking for access (docs/SECURITY.md, "Enrolment"): enrolled by the lab and not
 * yet approved, so not in the fleet and obeying nobody. Each row shows who asks — the JID, and from its vCard the
 * nickname, UUID and the QR code of its inventory — so that whoever approves it on the lab's server knows which robot
 * it is. Hidden while nobody asks. The approval itself is the server's ({@code ./sabot enrol approve JID}): the
 * workbench's account administers no group.
 */
final class AccessRequests {

    /** The section's column titles. */
    static final List<String> COLUMNS = List.of("Asking for access", "UUID");
    private static final int QR_PIXELS = 48;

    private final Table table;
    private final GridData layout;
    /** Identities by JID, fetched once each (null while the vCard is on its way or when there is none). */
    private final Map<String, RobotIdentity> identities = new HashMap<>();
    private final Map<String, Image> images = new HashMap<>();
    private List<String> shown = List.of();

    AccessRequests(Composite parent) {
        table = new Table(parent, SWT.BORDER | SWT.FULL_SELECTION | SWT.SINGLE);
        table.setHeaderVisible(true);
        table.setLinesVisible(true);
        table.setToolTipText(FleetView.ACCESS_REQUESTS_TOOLTIP);
        int[] widths = { 420, 360 };
        for (int i = 0; i < COLUMNS.size(); i++) {
            TableColumn c = new TableColumn(table, SWT.LEFT);
            c.setText(COLUMNS.get(i));
            c.setWidth(widths[i]);
        }
        layout = GridDataFactory.fillDefaults().grab(true, false).hint(SWT.DEFAULT, 0).create();
        layout.exclude = true;
        table.setLayoutData(layout);
        table.setVisible(false);
        table.addDisposeListener(e -> images.values().forEach(Image::dispose));
    }

    /**
     * UI thread: shows {@code asking}, fetching each new robot's identity from {@code fleet} (null: none available).
     */
    void show(List<String> asking, FleetState fleet) {
        if (table.isDisposed() || asking.equals(shown)) {
            return;
        }
        shown = List.copyOf(asking);
        for (String jid : asking) {
            if (!identities.containsKey(jid) && fleet != null) {
                identities.put(jid, null);
                fleet.identity(jid).whenComplete((identity, failure) -> {
                    if (identity != null && !table.isDisposed()) {
                        table.getDisplay().asyncExec(() -> {
                            identities.put(jid, identity);
                            rows();
                        });
                    }
                });
            }
        }
        rows();
    }

    private void rows() {
        if (table.isDisposed()) {
            return;
        }
        table.removeAll();
        for (String jid : shown) {
            RobotIdentity id = identities.get(jid);
            TableItem item = new TableItem(table, SWT.NONE);
            item.setText(texts(jid, id).toArray(String[]::new));
            Image qr = id == null ? null : qr(jid, id);
            if (qr != null) {
                item.setImage(0, qr);
            }
        }
        boolean hide = shown.isEmpty();
        if (layout.exclude != hide) {
            layout.exclude = hide;
            table.setVisible(!hide);
        }
        layout.heightHint = hide ? 0 : table.getHeaderHeight() + shown.size() * table.getItemHeight() + 4;
        table.getParent().layout(true, true);
    }

    /** @return a row's texts: who asks (nickname and JID), its UUID (or why it is not known yet) */
    static List<String> texts(String jid, RobotIdentity id) {
        if (id == null) {
            return List.of(jid, "(its vCard: not read yet)");
        }
        String name = id.nickname() == null ? jid : id.nickname() + " <" + jid + ">";
        return List.of(name, id.uid());
    }

    /** @return the QR code of the robot's inventory, scaled for a row; null when its vCard has none or it is no PNG */
    private Image qr(String jid, RobotIdentity id) {
        Image known = images.get(jid);
        if (known != null || id.qrPng() == null) {
            return known;
        }
        try {
            ImageData data = new ImageData(new ByteArrayInputStream(id.qrPng())).scaledTo(QR_PIXELS, QR_PIXELS);
            Image image = new Image(table.getDisplay(), data);
            images.put(jid, image);
            return image;
        } catch (SWTException notAnImage) {
            return null;
        }
    }

    /** @return the rows' texts, in order (for tests) */
    List<List<String>> rowTexts() {
        return java.util.Arrays.stream(table.getItems()).map(i -> List.of(i.getText(0), i.getText(1))).toList();
    }

    /** @return the section's table (for tests and screenshots) */
    Table table() {
        return table;
    }
}
