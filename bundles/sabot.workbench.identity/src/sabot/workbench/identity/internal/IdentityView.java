package sabot.workbench.identity.internal;

import java.io.ByteArrayInputStream;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.util.LinkedHashMap;
import java.util.Locale;
import java.util.Map;

import org.eclipse.swt.SWT;
import org.eclipse.swt.graphics.Image;
import org.eclipse.swt.graphics.ImageData;
import org.eclipse.swt.layout.GridData;
import org.eclipse.swt.layout.GridLayout;
import org.eclipse.swt.widgets.Button;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.FileDialog;
import org.eclipse.swt.widgets.Label;
import org.eclipse.swt.widgets.Text;

import sabot.identity.IdentityResult;
import sabot.identity.Inventory;
import sabot.identity.QrInventory;
import sabot.workbench.fleet.RobotIdentity;
import sabot.workbench.fleet.RobotState;
import sabot.workbench.robotview.RobotView;

/**
 * A robot's identity card, from its vCard ({@link sabot.workbench.fleet.FleetState#identity}): JID, nickname, URL,
 * location, UUID, and its QR-code inventory image, decoded here to show what it says (sabot.identity's codec) and saved
 * as a PNG on request, byte for byte as the robot published it.
 */
public final class IdentityView extends RobotView {

    public static final String ID = "sabot.workbench.identity.view";
    /** The fields shown, in order. */
    public static final String[] FIELDS = { "JID", "Nickname", "URL", "Location", "UUID", "Device", "Inventory" };

    private final Map<String, Text> values = new LinkedHashMap<>();
    private Label qr;
    private Image qrImage;
    private Button save;
    private RobotIdentity shown;

    @Override
    protected void createContent(Composite parent) {
        parent.setLayout(new GridLayout(3, false));
        for (String f : FIELDS) {
            new Label(parent, SWT.NONE).setText(f + ":");
            Text t = new Text(parent, SWT.READ_ONLY | SWT.SINGLE);
            t.setLayoutData(new GridData(SWT.FILL, SWT.CENTER, true, false));
            values.put(f, t);
            if (values.size() == 1) {
                qr = new Label(parent, SWT.BORDER);
                GridData g = new GridData(SWT.RIGHT, SWT.TOP, false, false, 1, FIELDS.length + 1);
                g.widthHint = 200;
                g.heightHint = 200;
                qr.setLayoutData(g);
            }
        }
        Composite buttons = new Composite(parent, SWT.NONE);
        buttons.setLayout(new GridLayout(2, true));
        buttons.setLayoutData(new GridData(SWT.LEFT, SWT.TOP, false, false, 2, 1));
        Button reload = new Button(buttons, SWT.PUSH);
        reload.setText("Reload");
        reload.addListener(SWT.Selection, e -> load());
        save = new Button(buttons, SWT.PUSH);
        save.setText("Save QR as PNG...");
        save.setEnabled(false);
        save.addListener(SWT.Selection, e -> {
            FileDialog d = new FileDialog(save.getShell(), SWT.SAVE);
            d.setFilterExtensions(new String[] { "*.png" });
            d.setFileName(shown.jid().replace('@', '_') + "-inventory.png");
            d.setOverwrite(true);
            String file = d.open();
            if (file != null) {
                saveQr(Paths.get(file));
            }
        });
    }

    @Override
    protected void robotChanged(RobotState state, boolean newRobot) {
        if (newRobot) {
            show(null);
            if (state != null) {
                load();
            }
        }
    }

    /** Fetches the chosen robot's vCard again. */
    public void load() {
        request("identity", (fleet, jid) -> fleet.identity(jid), this::show);
    }

    /** Shows an identity as a fetched one is shown (null clears the view). */
    public void display(RobotIdentity id) {
        show(id);
    }

    private void show(RobotIdentity id) {
        shown = id;
        Map<String, String> text = texts(id);
        for (Map.Entry<String, Text> e : values.entrySet()) {
            e.getValue().setText(text.getOrDefault(e.getKey(), ""));
        }
        if (qrImage != null) {
            qrImage.dispose();
            qrImage = null;
        }
        if (id != null && id.qrPng() != null) {
            qrImage = new Image(qr.getDisplay(), new ImageData(new ByteArrayInputStream(id.qrPng())));
        }
        qr.setImage(qrImage);
        save.setEnabled(id != null && id.qrPng() != null);
        qr.getParent().layout(true, true);
    }

    /** @return what the view shows of an identity, by field name ({@link #FIELDS}); empty for null */
    static Map<String, String> texts(RobotIdentity id) {
        Map<String, String> m = new LinkedHashMap<>();
        if (id == null) {
            return m;
        }
        m.put("JID", id.jid());
        m.put("Nickname", orDash(id.nickname()));
        m.put("URL", orDash(id.url()));
        m.put("Location", id.latitude() == null ? "unknown" : String.format(Locale.ROOT, "%.6f, %.6f", id.latitude(),
                id.longitude()));
        m.put("UUID", id.uid());
        m.put("Device", id.category() + ", " + id.manufacturer() + (id.model() == null ? "" : " " + id.model()));
        m.put("Inventory", inventory(id.qrPng()));
        return m;
    }

    private static String inventory(byte[] png) {
        if (png == null) {
            return "no QR code in the vCard";
        }
        IdentityResult<Inventory> r = QrInventory.decode(png);
        if (r instanceof IdentityResult.Err<Inventory> e) {
            return "QR code unreadable: " + e.text();
        }
        Inventory inv = r.orElseThrow();
        return inv.mechanic().model() + ": " + inv.boards().size() + " board(s), " + inv.specialDevices().size()
                + " device(s)";
    }

    private static String orDash(String s) {
        return s == null || s.isEmpty() ? "-" : s;
    }

    /** Writes the QR-code image as the robot published it. */
    public void saveQr(Path file) {
        if (shown == null || shown.qrPng() == null) {
            showMessage("no QR code to save", true);
            return;
        }
        try {
            Files.write(file, shown.qrPng());
            showMessage(shown.jid() + ": QR inventory saved to " + file, false);
        } catch (IOException e) {
            showMessage("saving " + file + ": " + e.getMessage(), true);
        }
    }

    /** @return the field texts shown now, by name */
    public Map<String, String> shownTexts() {
        Map<String, String> m = new LinkedHashMap<>();
        values.forEach((k, t) -> m.put(k, t.getText()));
        return m;
    }

    /** @return the identity shown, or null */
    public RobotIdentity shown() {
        return shown;
    }

    @Override
    public void dispose() {
        if (qrImage != null) {
            qrImage.dispose();
        }
        super.dispose();
    }
}
