package sabot.workbench.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.nio.file.StandardCopyOption;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;

import org.eclipse.core.runtime.preferences.InstanceScope;
import org.eclipse.jface.preference.PreferenceDialog;
import org.eclipse.swt.SWT;
import org.eclipse.swt.graphics.ImageData;
import org.eclipse.swt.graphics.ImageLoader;
import org.eclipse.swt.widgets.Canvas;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Control;
import org.eclipse.swt.widgets.Display;
import org.eclipse.swt.widgets.Event;
import org.eclipse.swt.widgets.MenuItem;
import org.eclipse.swt.widgets.Shell;
import org.eclipse.swt.widgets.TableColumn;
import org.eclipse.swt.widgets.Text;
import org.eclipse.ui.IWorkbenchPage;
import org.eclipse.ui.IWorkbenchWindow;
import org.eclipse.ui.PlatformUI;
import org.eclipse.ui.dialogs.PreferencesUtil;
import org.junit.jupiter.api.MethodOrderer;
import org.junit.jupiter.api.Order;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.TestMethodOrder;
import org.osgi.service.prefs.Preferences;

import sabot.workbench.account.XmppAccountStore;
import sabot.workbench.map.MapViewport;
import sabot.workbench.views.FleetView;
import sabot.workbench.views.WorkspaceView;

/** The real workbench window, driven on the UI thread under Xvfb. The screenshot is taken first, untouched. */
@TestMethodOrder(MethodOrderer.OrderAnnotation.class)
public class WorkbenchUiTest {

    private static IWorkbenchWindow window() {
        IWorkbenchWindow w = PlatformUI.getWorkbench().getActiveWorkbenchWindow();
        assertNotNull(w, "no workbench window");
        return w;
    }

    private static void flush() {
        Display d = Display.getCurrent();
        while (d.readAndDispatch()) {
            // process pending layout and paint events
        }
    }

    @Test
    @Order(1)
    void windowShowsWorkspaceAndFleetViewsAndMenusAndIsCaptured() throws Exception {
        IWorkbenchPage page = window().getActivePage();
        WorkspaceView workspace = (WorkspaceView) page.findView(WorkspaceView.ID);
        FleetView fleet = (FleetView) page.findView(FleetView.ID);
        assertNotNull(workspace, "workspace view not open");
        assertNotNull(fleet, "fleet view not open");
        assertEquals(FleetView.COLUMNS, Arrays.stream(fleet.table().getColumns()).map(TableColumn::getText).toList());
        assertEquals(0, fleet.table().getItemCount());

        Shell shell = window().getShell();
        List<String> menus = Arrays.stream(shell.getMenuBar().getItems()).map(MenuItem::getText).toList();
        assertEquals(List.of("&File", "&Robot", "&Window", "&Help"), menus);
        assertEquals("Sabot Workbench", shell.getText());

        flush();
        Path dir = Paths.get(System.getProperty("sabot.screenshots", "target/screenshots"));
        Path png = dir.resolve("workbench-start.png");
        SabotWindowAdvisor.saveScreenshot(shell, png);
        ImageData image = new ImageLoader().load(png.toString())[0];
        assertTrue(image.width >= 800 && image.height >= 500, image.width + "x" + image.height);
        assertTrue(distinctColours(image) > 4, "the screenshot is blank");
        String root = System.getProperty("sabot.root");
        if (root != null && Files.isDirectory(Paths.get(root, "docs"))) {
            Path docs = Paths.get(root, "docs", "images");
            Files.createDirectories(docs);
            Files.copy(png, docs.resolve("workbench-start.png"), StandardCopyOption.REPLACE_EXISTING);
        }
    }

    @Test
    void wheelZoomsAtThePointerAndDragPans() {
        WorkspaceView workspace = (WorkspaceView) window().getActivePage().findView(WorkspaceView.ID);
        Canvas canvas = find(window().getShell(), Canvas.class, c -> c.isVisible() && c.getParent() != null
                && c.getSize().x > 400);
        MapViewport v = workspace.viewport();
        double scale = v.scale();
        double mx = v.toMapX(200);
        double my = v.toMapY(150);

        Event wheel = new Event();
        wheel.x = 200;
        wheel.y = 150;
        wheel.count = 3;
        canvas.notifyListeners(SWT.MouseVerticalWheel, wheel);
        assertEquals(scale * 1.2, v.scale(), 1e-9);
        assertEquals(mx, v.toMapX(200), 1e-9);
        assertEquals(my, v.toMapY(150), 1e-9);

        double before = v.toScreenX(0);
        mouse(canvas, SWT.MouseDown, 100, 100);
        mouse(canvas, SWT.MouseMove, 160, 100);
        mouse(canvas, SWT.MouseUp, 160, 100);
        assertEquals(before + 60, v.toScreenX(0), 1e-9);

        workspace.home();
        assertEquals(5, v.centerX(), 1e-9);
    }

    @Test
    void preferencePageKeepsThePasswordOutOfThePreferences() throws Exception {
        XmppAccountStore store = XmppAccountPreferencePage.defaultStore();
        store.forgetPassword();
        PreferenceDialog dialog = PreferencesUtil.createPreferenceDialogOn(window().getShell(),
                "sabot.workbench.preferences.xmpp", null, null);
        dialog.setBlockOnOpen(false);
        dialog.open();
        try {
            XmppAccountPreferencePage page = (XmppAccountPreferencePage) dialog.getSelectedPage();
            List<Text> fields = all(page.getControl(), Text.class);
            assertEquals(6, fields.size());
            fields.get(0).setText("");
            assertFalse(page.isValid());
            assertEquals("Server is empty", page.getErrorMessage());
            fields.get(0).setText("127.0.0.1,");
            assertFalse(page.isValid());
            assertEquals("Server: an empty name in the list (several servers are comma-separated: a,b)", page
                    .getErrorMessage());
            fields.get(0).setText("127.0.0.1");
            fields.get(1).setText("not-a-port");
            assertFalse(page.isValid());
            assertEquals("Port must be between 1 and 65535", page.getErrorMessage());
            fields.get(2).setText("operator@sabot.local/desk");
            fields.get(1).setText("15222");
            assertEquals("JID must look like name@domain (no resource, no spaces)", page.getErrorMessage());
            fields.get(2).setText("operator@sabot.local");
            fields.get(3).setText("s3cret-pw");
            fields.get(4).setText("fleet@conference.sabot.local/nick");
            assertFalse(page.isValid());
            assertTrue(page.getErrorMessage().startsWith("Fleet lobby must look like name@domain"), page
                    .getErrorMessage());
            fields.get(4).setText("fleet@conference.sabot.local");
            assertTrue(page.isValid());
            // the lab CA: a file that is not there is refused; a CA's certificate shows its fingerprint
            java.nio.file.Path dir = Files.createTempDirectory("wb-ca");
            fields.get(5).setText(dir.resolve("missing.pem").toString());
            assertFalse(page.isValid());
            assertEquals("CA file " + dir.resolve("missing.pem") + " cannot be read", page.getErrorMessage());
            java.nio.file.Path ca = sabot.testsupport.xmpp.TestCertificates.anotherCa(dir, "lab-ca");
            fields.get(5).setText(ca.toString());
            assertTrue(page.isValid(), page.getErrorMessage());
            String fingerprint = sabot.fleet.ServerTrust.labCa(ca).fingerprints().get(0);
            assertTrue(all(page.getControl(), org.eclipse.swt.widgets.Label.class).stream().anyMatch(l -> l.getText()
                    .equals("TLS with this CA only, SHA-256 " + fingerprint)), "no fingerprint shown");
            assertTrue(page.performOk());
        } finally {
            dialog.close();
        }

        Preferences prefs = InstanceScope.INSTANCE.getNode("sabot.workbench");
        assertEquals("operator@sabot.local", prefs.get("xmpp.jid", null));
        assertEquals(15222, prefs.getInt("xmpp.port", 0));
        assertTrue(prefs.get("xmpp.caFile", "").endsWith("lab-ca.pem"), prefs.get("xmpp.caFile", ""));
        assertTrue(store.load().caFile().endsWith("lab-ca.pem"));
        assertEquals("fleet@conference.sabot.local", store.loadLobby());
        store.saveLobby("");
        assertEquals("", store.loadLobby());
        for (String key : prefs.keys()) {
            assertFalse(prefs.get(key, "").contains("s3cret-pw"), "password leaked into preference " + key);
        }
        assertEquals("rw-------", PosixFilePermissions.toString(Files.getPosixFilePermissions(store.passwordFile())));
        assertEquals("s3cret-pw", new String(store.loadPassword()));

        Files.setPosixFilePermissions(store.passwordFile(), PosixFilePermissions.fromString("rw-r--r--"));
        Exception loose = org.junit.jupiter.api.Assertions.assertThrows(java.io.IOException.class,
                store::loadPassword);
        assertTrue(loose.getMessage().contains("chmod 600"), loose.getMessage());
        store.forgetPassword();
        assertNull(store.loadPassword());
    }

    @Test
    void operationPerspectiveIsTheDefaultWithWorkspaceCentreFleetBelowAndPluginFolder() {
        IWorkbenchPage page = window().getActivePage();
        assertEquals(OperationPerspective.ID, PlatformUI.getWorkbench().getPerspectiveRegistry()
                .getDefaultPerspective());
        assertEquals(OperationPerspective.ID, page.getPerspective().getId());
        assertEquals("Operation", page.getPerspective().getLabel());
        WorkspaceView workspace = (WorkspaceView) page.findView(WorkspaceView.ID);
        FleetView fleet = (FleetView) page.findView(FleetView.ID);
        flush();
        org.eclipse.swt.graphics.Rectangle map = workspace.canvas().getDisplay().map(workspace.canvas(), null,
                workspace.canvas().getBounds());
        org.eclipse.swt.graphics.Rectangle table = fleet.table().getDisplay().map(fleet.table(), null, fleet.table()
                .getBounds());
        assertTrue(table.y >= map.y + map.height, "Fleet " + table + " is not below the Workspace " + map);
        assertTrue(map.width > 800, "the Workspace takes the width: " + map);
        // Window > Show View: the shortcuts of the perspective, and the Sabot category of the view registry
        assertTrue(List.of(page.getShowViewShortcuts()).containsAll(List.of(WorkspaceView.ID, FleetView.ID)), List.of(
                page.getShowViewShortcuts()).toString());
        org.eclipse.ui.views.IViewCategory sabot = Arrays.stream(PlatformUI.getWorkbench().getViewRegistry()
                .getCategories()).filter(c -> c.getLabel().equals("Sabot")).findFirst().orElseThrow(
                        () -> new AssertionError("no Sabot category in Show View"));
        List<String> views = Arrays.stream(sabot.getViews()).map(v -> v.getId()).toList();
        assertTrue(views.containsAll(List.of(WorkspaceView.ID, FleetView.ID)), views.toString());
    }

    @Test
    void stopAllIsInTheRobotMenuTheToolbarAndBoundToCtrlShiftHWithoutClash() {
        IWorkbenchWindow w = window();
        org.eclipse.ui.keys.IBindingService bindings = w.getService(org.eclipse.ui.keys.IBindingService.class);
        org.eclipse.jface.bindings.keys.KeySequence key = org.eclipse.jface.bindings.keys.KeySequence.getInstance(
                org.eclipse.jface.bindings.keys.KeyStroke.getInstance(SWT.MOD1 | SWT.MOD2, 'H'));
        List<org.eclipse.jface.bindings.Binding> onKey = Arrays.stream(bindings.getBindings()).filter(b -> b
                .getTriggerSequence().equals(key) && b.getSchemeId().equals(bindings.getActiveScheme().getId()))
                .toList();
        assertEquals(1, onKey.size(), "bindings of Ctrl+Shift+H: " + onKey);
        assertEquals(StopAllHandler.COMMAND_ID, onKey.get(0).getParameterizedCommand().getId());
        assertEquals(WorkspaceView.FLEET_CONTEXT, onKey.get(0).getContextId());

        MenuItem robot = Arrays.stream(w.getShell().getMenuBar().getItems()).filter(i -> i.getText().equals("&Robot"))
                .findFirst().orElseThrow();
        // the menu is filled when shown
        robot.getMenu().notifyListeners(SWT.Show, new Event());
        List<String> items = Arrays.stream(robot.getMenu().getItems()).map(MenuItem::getText).toList();
        assertTrue(items.stream().anyMatch(t -> t.startsWith("&Stop All Robots")), items.toString());
        robot.getMenu().notifyListeners(SWT.Hide, new Event());

        List<org.eclipse.swt.widgets.ToolItem> tools = all(w.getShell(), org.eclipse.swt.widgets.ToolBar.class)
                .stream().flatMap(t -> Arrays.stream(t.getItems())).toList();
        assertTrue(tools.stream().anyMatch(t -> "Stop All Robots".equals(t.getText()) || String.valueOf(t
                .getToolTipText()).startsWith("Stop all robots")), tools.stream().map(t -> t.getText() + "/" + t
                        .getToolTipText()).toList().toString());
    }

    /** A key pressed on a control, as SWT delivers it to the control's listeners ({@code SWT.KeyDown}). */
    public static void key(Control c, int keyCode, char character, int stateMask) {
        Event e = new Event();
        e.keyCode = keyCode;
        e.character = character;
        e.stateMask = stateMask;
        c.notifyListeners(SWT.KeyDown, e);
    }

    /** A left-button mouse event at (x, y), as SWT delivers it to the control's listeners. */
    public static void mouse(Control c, int type, int x, int y) {
        Event e = new Event();
        e.x = x;
        e.y = y;
        e.button = 1;
        c.notifyListeners(type, e);
    }

    private static int distinctColours(ImageData image) {
        java.util.Set<Integer> colours = new java.util.HashSet<>();
        for (int y = 0; y < image.height; y += 7) {
            for (int x = 0; x < image.width; x += 7) {
                colours.add(image.getPixel(x, y));
            }
        }
        return colours.size();
    }

    /** @return the first control of {@code type} under {@code root} (itself included) that {@code filter} accepts */
    public static <T extends Control> T find(Control root, Class<T> type, java.util.function.Predicate<T> filter) {
        for (T c : all(root, type)) {
            if (filter.test(c)) {
                return c;
            }
        }
        throw new AssertionError("no " + type.getSimpleName() + " found");
    }

    private static <T extends Control> List<T> all(Control root, Class<T> type) {
        List<T> found = new ArrayList<>();
        collect(root, type, found);
        return found;
    }

    private static <T extends Control> void collect(Control c, Class<T> type, List<T> found) {
        if (type.isInstance(c)) {
            found.add(type.cast(c));
        }
        if (c instanceof Composite composite) {
            for (Control child : composite.getChildren()) {
                collect(child, type, found);
            }
        }
    }
}
