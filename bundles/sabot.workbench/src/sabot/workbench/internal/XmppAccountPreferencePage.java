package sabot.workbench.internal;

import java.io.IOException;

import org.eclipse.jface.layout.GridDataFactory;
import org.eclipse.jface.layout.GridLayoutFactory;
import org.eclipse.jface.preference.PreferencePage;
import org.eclipse.swt.SWT;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Control;
import org.eclipse.swt.widgets.Label;
import org.eclipse.swt.widgets.Text;
import org.eclipse.ui.IWorkbench;
import org.eclipse.ui.IWorkbenchPreferencePage;

import sabot.fleet.ServerTrust;
import sabot.workbench.account.XmppAccount;
import sabot.workbench.account.XmppAccountStore;

/**
 * Window &gt; Preferences &gt; XMPP Account: server, port, JID and password of the operator's account, and the lab CA
 * that signs the server's certificate (its SHA-256 fingerprint shown, to compare with the one the server's
 * administrator gives). The password goes to an owner-only (0600) file, never into the preferences; an empty password
 * field keeps the stored one. The connection always requires TLS.
 */
public final class XmppAccountPreferencePage extends PreferencePage implements IWorkbenchPreferencePage {

    private XmppAccountStore store;
    private Text server;
    private Text port;
    private Text jid;
    private Text password;
    private Text lobby;
    private Text caFile;
    private Label fingerprint;

    /** @return the store the workbench uses for the operator's account */
    public static XmppAccountStore defaultStore() {
        return XmppAccountStore.workbenchStore();
    }

    @Override
    public void init(IWorkbench workbench) {
        store = defaultStore();
        setDescription("The account the workbench uses to reach the fleet over XMPP.");
    }

    @Override
    protected Control createContents(Composite parent) {
        Composite c = new Composite(parent, SWT.NONE);
        GridLayoutFactory.swtDefaults().numColumns(2).applyTo(c);
        XmppAccount account = store.load();
        server = field(c, "&Server:", account.server(), SWT.BORDER);
        server.setMessage("host or address; a cluster's nodes comma-separated: a,b");
        port = field(c, "&Port:", Integer.toString(account.port()), SWT.BORDER);
        jid = field(c, "&JID:", account.jid(), SWT.BORDER);
        password = field(c, "Pass&word:", "", SWT.BORDER | SWT.PASSWORD);
        password.setMessage(store.hasPassword() ? "(stored; type to replace)" : "(not stored)");
        lobby = field(c, "Fleet &lobby:", store.loadLobby(), SWT.BORDER);
        lobby.setMessage("(none) e.g. fleet@conference.sabot.local: online robots found there are followed");
        caFile = field(c, "Lab &CA file:", account.caFile(), SWT.BORDER);
        caFile.setMessage("(none: the authorities the JVM trusts) e.g. the ca/ca.pem of ./sabot xmpp start");
        fingerprint = new Label(c, SWT.WRAP);
        GridDataFactory.fillDefaults().span(2, 1).grab(true, false).hint(400, SWT.DEFAULT).applyTo(fingerprint);
        Label where = new Label(c, SWT.WRAP);
        where.setText("The password is kept in " + store.passwordFile() + ", readable by you only (mode 0600).");
        GridDataFactory.fillDefaults().span(2, 1).grab(true, false).hint(400, SWT.DEFAULT).applyTo(where);
        validate();
        return c;
    }

    private Text field(Composite parent, String label, String value, int style) {
        new Label(parent, SWT.NONE).setText(label);
        Text text = new Text(parent, style);
        text.setText(value);
        GridDataFactory.fillDefaults().grab(true, false).applyTo(text);
        text.addModifyListener(e -> validate());
        return text;
    }

    /** @return the account as typed, or null (with the page's error message set) when it is invalid */
    private XmppAccount validate() {
        int p;
        try {
            p = Integer.parseInt(port.getText().strip());
        } catch (NumberFormatException e) {
            p = -1;
        }
        XmppAccount account = new XmppAccount(server.getText(), p, jid.getText(), caFile == null ? ""
                : caFile.getText());
        String problem = account.problem();
        if (problem == null && fingerprint != null) {
            problem = showTrust(account.caFile());
        }
        String room = lobby == null ? "" : lobby.getText().strip();
        if (problem == null && !room.isEmpty()) {
            String roomProblem = new XmppAccount(account.server(), account.port(), room).problem();
            problem = roomProblem == null ? null : "Fleet lobby " + roomProblem.replaceFirst("^JID ", "");
        }
        setErrorMessage(problem);
        setValid(problem == null);
        return problem == null ? account : null;
    }

    /** Shows what the connection will trust; @return the CA file's problem, or null */
    private String showTrust(String file) {
        try {
            ServerTrust trust = ServerTrust.of(file);
            fingerprint.setText(file.isBlank() ? "TLS with the authorities the JVM trusts."
                    : "TLS with this CA only, SHA-256 " + String.join(", ", trust.fingerprints()));
            return null;
        } catch (IOException e) {
            fingerprint.setText("");
            return "Lab CA file: " + e.getMessage();
        }
    }

    @Override
    public boolean performOk() {
        XmppAccount account = validate();
        if (account == null) {
            return false;
        }
        char[] typed = password.getText().toCharArray();
        try {
            store.saveLobby(lobby.getText());
            store.save(account, typed.length == 0 ? null : typed);
            password.setText("");
            return true;
        } catch (IOException | IllegalArgumentException e) {
            setErrorMessage("Cannot save the account: " + e.getMessage());
            return false;
        }
    }

    @Override
    protected void performDefaults() {
        port.setText(Integer.toString(XmppAccount.DEFAULT_PORT));
        super.performDefaults();
    }
}
