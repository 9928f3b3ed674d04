package sabot.products.uidriver;

import java.io.IOException;
import java.net.URI;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.Paths;
import java.nio.file.StandardOpenOption;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Set;
import java.util.concurrent.Callable;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicReference;
import java.util.concurrent.locks.LockSupport;
import java.util.function.Predicate;

import org.eclipse.core.runtime.Adapters;
import org.eclipse.equinox.p2.engine.IProfile;
import org.eclipse.equinox.p2.engine.IProfileRegistry;
import org.eclipse.equinox.p2.metadata.IInstallableUnit;
import org.eclipse.equinox.p2.query.IQueryResult;
import org.eclipse.equinox.p2.query.QueryUtil;
import org.eclipse.equinox.p2.ui.ProvisioningUI;
import org.eclipse.swt.SWT;
import org.eclipse.swt.graphics.GC;
import org.eclipse.swt.graphics.Image;
import org.eclipse.swt.graphics.ImageData;
import org.eclipse.swt.graphics.ImageLoader;
import org.eclipse.swt.graphics.Rectangle;
import org.eclipse.swt.widgets.Button;
import org.eclipse.swt.widgets.Combo;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Control;
import org.eclipse.swt.widgets.Display;
import org.eclipse.swt.widgets.Event;
import org.eclipse.swt.widgets.Label;
import org.eclipse.swt.widgets.Link;
import org.eclipse.swt.widgets.Menu;
import org.eclipse.swt.widgets.MenuItem;
import org.eclipse.swt.widgets.ProgressBar;
import org.eclipse.swt.widgets.Shell;
import org.eclipse.swt.widgets.Table;
import org.eclipse.swt.widgets.TableItem;
import org.eclipse.swt.widgets.Tree;
import org.eclipse.swt.widgets.TreeItem;
import org.eclipse.swt.widgets.Widget;
import org.eclipse.ui.IWorkbenchWindow;
import org.eclipse.ui.PlatformUI;
import org.eclipse.ui.handlers.IHandlerService;
import org.osgi.framework.Bundle;
import org.osgi.framework.BundleContext;
import org.osgi.framework.Version;

/**
 * Drives the real p2 UI of Sabot Workbench the way an operator does (SWTBot is not on Maven Central): menus read by
 * firing {@code SWT.Show}, commands run through the handler service, wizard widgets found in the shells, checked,
 * selected and pressed by sending them the SWT events their listeners wait for. Every widget access happens on the UI
 * thread ({@code syncExec}); presses that may open a modal dialog go through {@code asyncExec}, so this thread is never
 * stuck inside a nested event loop.
 *
 * <p>
 * Steps (system property {@value #STEPS}, comma separated) survive restarts: each one done is appended to the state
 * file ({@value #STATE}), and the workbench relaunched by its start script (exit code 23) goes on with the first step
 * not done. Steps: {@code splash} (watch the splash: image, progress past a quarter, a "Loading" line; runs beside the
 * others from the start), {@code menu} (Help lists Install New Software... and Check for Updates), {@code install}
 * (Install New Software...: our preconfigured site, its category, the feature {@value #FEATURE} checked, Next, Finish,
 * trust the unsigned content, Restart Now), {@code verify} (the feature is in the profile, its bundle {@value #BUNDLE}
 * resolved), {@code noupdate} (Check for Updates finds nothing), {@code addsite} (a second site, {@value #SITE2}, added
 * as Available Software Sites does), {@code update} (Check for Updates lists the feature at version {@value #VERSION},
 * Finish, trust, Restart Now), {@code verifyupdate} (that version in the profile, the bundle at
 * {@value #BUNDLE_VERSION}), {@code exit} (closes the workbench).
 *
 * <p>
 * Output: one console line per step, {@code UIDRIVER <step> ok: ...}; on a failure {@code UIDRIVER FAILED <step>: ...}
 * and the JVM halts with {@value #FAILED_EXIT} (modal dialogs may be open: a normal close could hang).
 */
final class UiDriver implements Runnable {

    static final String STEPS = "sabot.uidriver.steps";
    static final String STATE = "sabot.uidriver.state";
    static final String SHOTS = "sabot.uidriver.shots";
    static final String FEATURE = "sabot.uidriver.feature";
    static final String BUNDLE = "sabot.uidriver.bundle";
    static final String CATEGORY = "sabot.uidriver.category";
    static final String SITE_NAME = "sabot.uidriver.siteName";
    static final String SITE2 = "sabot.uidriver.site2";
    static final String VERSION = "sabot.uidriver.version";
    static final String BUNDLE_VERSION = "sabot.uidriver.bundleVersion";

    static final int FAILED_EXIT = 86;
    /** Upper bound of one wait (a window, a dialog, a resolution); the whole test has its own. */
    private static final long WAIT_S = 60;
    /** How often a condition is probed while waiting for it. */
    private static final long PROBE_MS = 50;

    private final BundleContext context;
    private final List<String> steps;
    private final Path state;
    private final Path shots;
    private Display display;

    UiDriver(BundleContext context, String steps) {
        this.context = context;
        this.steps = Arrays.stream(steps.split(",")).map(String::trim).filter(s -> !s.isEmpty()).toList();
        this.state = Paths.get(require(STATE));
        String s = System.getProperty(SHOTS);
        this.shots = s == null ? null : Paths.get(s);
    }

    @Override
    public void run() {
        String step = "start";
        try {
            Set<String> done = done();
            display = await("the display", () -> findDisplay());
            if (steps.contains("splash") && !done.contains("splash")) {
                watchSplash();
            }
            step = "workbench";
            await("the workbench window", () -> PlatformUI.isWorkbenchRunning() && ui(() -> {
                IWorkbenchWindow w = PlatformUI.getWorkbench().getActiveWorkbenchWindow();
                return w != null && w.getShell().isVisible() && !PlatformUI.getWorkbench().isStarting();
            }));
            for (String s : steps) {
                step = s;
                if (done.contains(s) || s.equals("splash")) {
                    continue;
                }
                switch (s) {
                    case "menu" -> menu();
                    case "install" -> install();
                    case "verify" -> verify(require(FEATURE) + ".feature.group", null, null);
                    case "noupdate" -> noUpdate();
                    case "addsite" -> addSite();
                    case "update" -> update();
                    case "verifyupdate" -> verify(require(FEATURE) + ".feature.group", require(VERSION),
                            require(BUNDLE_VERSION));
                    case "exit" -> exit();
                    default -> throw new IllegalArgumentException("unknown step '" + s + "'");
                }
                if (s.equals("install") || s.equals("update")) {
                    return; // recorded before Restart Now; the next step runs in the relaunched workbench
                }
                markDone(s);
                if (s.equals("exit")) {
                    return;
                }
            }
        } catch (Throwable t) {
            fail(step, t);
        }
    }

    // --- steps --------------------------------------------------------------------------------------------------

    /** The splash shell with its bar past a quarter and a "Loading ..." line, captured; checked until the window. */
    private void watchSplash() {
        AtomicReference<String> seen = new AtomicReference<>();
        AtomicReference<String> last = new AtomicReference<>("nothing");
        Thread watcher = new Thread(() -> {
            try {
                long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(WAIT_S);
                boolean splashSeen = false;
                while (seen.get() == null) {
                    // runs when the UI thread spins: the splash handler does after each bundle started
                    AtomicReference<Boolean> present = new AtomicReference<>(false);
                    syncExecOnceCreated(() -> {
                        for (Shell shell : display.getShells()) {
                            if (!Boolean.TRUE.equals(shell.getData("sabot.workbench.splash")) || shell.isDisposed()) {
                                continue;
                            }
                            present.set(true);
                            ProgressBar bar = first(shell, ProgressBar.class,
                                    b -> (b.getStyle() & SWT.INDETERMINATE) == 0 && b.isVisible());
                            Label line = first(shell, Label.class, l -> l.getText().startsWith("Loading "));
                            last.set("bar " + (bar == null ? "none" : bar.getSelection() + "/" + bar.getMaximum())
                                    + ", line " + (line == null ? "none" : "'" + line.getText() + "'"));
                            if (bar != null && line != null && bar.getSelection() * 4 >= bar.getMaximum()) {
                                Rectangle b = shell.getBounds();
                                String shot = shot(shell, "workbench-splash.png");
                                seen.set("image " + b.width + "x" + b.height + ", progress " + bar.getSelection() + "/"
                                        + bar.getMaximum() + ", message '" + line.getText() + "'" + shot);
                            }
                        }
                    });
                    splashSeen |= present.get();
                    if (seen.get() != null) {
                        break;
                    }
                    if (PlatformUI.isWorkbenchRunning() && !PlatformUI.getWorkbench().isStarting()) {
                        throw new AssertionError(splashSeen ? "the splash never showed a bar past a quarter with a "
                                + "'Loading' line; last seen: " + last.get() : "no splash shell (is the launcher's native library there, "
                                + "-showsplash given?)");
                    }
                    if (System.nanoTime() > deadline) {
                        throw new AssertionError("no splash within " + WAIT_S + " s");
                    }
                    LockSupport.parkNanos(TimeUnit.MILLISECONDS.toNanos(PROBE_MS));
                }
                markDone("splash");
                ok("splash", seen.get());
            } catch (Throwable t) {
                fail("splash", t);
            }
        }, "sabot-uidriver-splash");
        watcher.setDaemon(true);
        watcher.start();
    }

    private void menu() throws Exception {
        List<String> items = ui(() -> {
            Shell shell = PlatformUI.getWorkbench().getActiveWorkbenchWindow().getShell();
            Menu bar = shell.getMenuBar();
            for (MenuItem top : bar.getItems()) {
                if (plain(top.getText()).equals("Help") && top.getMenu() != null) {
                    Menu help = top.getMenu();
                    help.notifyListeners(SWT.Show, new Event()); // contributions are created when the menu shows
                    List<String> texts = new ArrayList<>();
                    for (MenuItem i : help.getItems()) {
                        texts.add((i.getStyle() & SWT.SEPARATOR) != 0 ? "---" : plain(i.getText()));
                    }
                    help.notifyListeners(SWT.Hide, new Event());
                    return texts;
                }
            }
            throw new AssertionError("no Help menu in " + Arrays.stream(bar.getItems()).map(MenuItem::getText)
                    .toList());
        });
        if (!items.contains("Install New Software...") || !items.contains("Check for Updates")) {
            throw new AssertionError("Help menu without the p2 items: " + items);
        }
        ok("menu", "Help menu " + items);
    }

    private void install() throws Exception {
        String siteName = require(SITE_NAME);
        String category = require(CATEGORY);
        String featureIu = require(FEATURE) + ".feature.group";
        runCommand("org.eclipse.equinox.p2.ui.sdk.install");
        Shell wizard = await("the Install wizard", () -> shellWith(s -> first(s, Combo.class, c -> true) != null
                && first(s, Tree.class, t -> (t.getStyle() & SWT.CHECK) != 0) != null));
        // the preconfigured site is offered without typing: select it
        String offered = ui(() -> {
            Combo combo = first(wizard, Combo.class, c -> true);
            for (int i = 0; i < combo.getItemCount(); i++) {
                if (combo.getItem(i).startsWith(siteName + " - ")) {
                    combo.select(i);
                    combo.notifyListeners(SWT.Selection, new Event());
                    return combo.getItem(i);
                }
            }
            throw new AssertionError("'Work with' does not offer '" + siteName + "': "
                    + Arrays.toString(combo.getItems()));
        });
        TreeItem[] feature = new TreeItem[1];
        String categoryText = await("category '" + category + "' and " + featureIu + " in the tree", () -> ui(() -> {
            Tree tree = first(wizard, Tree.class, t -> (t.getStyle() & SWT.CHECK) != 0);
            for (TreeItem item : tree.getItems()) {
                if (!item.getText(0).equals(category)) {
                    continue;
                }
                if (!item.getExpanded()) {
                    Event e = new Event();
                    e.item = item;
                    tree.notifyListeners(SWT.Expand, e); // the viewer creates the children on this event
                    item.setExpanded(true);
                }
                for (TreeItem child : item.getItems()) {
                    IInstallableUnit iu = Adapters.adapt(child.getData(), IInstallableUnit.class);
                    if (iu != null && iu.getId().equals(featureIu)) {
                        feature[0] = child;
                        return item.getText(0) + " > " + child.getText(0) + " " + child.getText(1);
                    }
                }
            }
            return null;
        }));
        ui(() -> {
            TreeItem item = feature[0];
            item.setChecked(true);
            Event e = new Event();
            e.item = item;
            e.detail = SWT.CHECK;
            item.getParent().notifyListeners(SWT.Selection, e); // CheckboxTreeViewer: check state changed
            return null;
        });
        await("Next to be enabled", () -> ui(() -> button(wizard, "Next >").isEnabled()));
        String shot = ui(() -> shot(wizard, "p2-install.png"));
        finishWizard(wizard, "Install Details");
        String trusted = trust();
        markDone("install"); // before the restart ends this JVM
        ok("install", "site '" + offered + "', " + categoryText + ", trusted " + trusted + shot + "; Restart Now");
        restartNow();
    }

    private void verify(String iuId, String version, String bundleVersion) throws Exception {
        ProvisioningUI ui = ProvisioningUI.getDefaultUI();
        IProfileRegistry registry = ui.getSession().getProvisioningAgent().getService(IProfileRegistry.class);
        IProfile profile = registry.getProfile(ui.getProfileId());
        if (profile == null) {
            throw new AssertionError("no profile " + ui.getProfileId() + " (not a p2-installed product?)");
        }
        IQueryResult<IInstallableUnit> found = profile.query(QueryUtil.createIUQuery(iuId), null);
        if (found.isEmpty()) {
            throw new AssertionError(iuId + " is not in profile " + profile.getProfileId());
        }
        IInstallableUnit iu = found.iterator().next();
        if (version != null && !iu.getVersion().toString().equals(version)) {
            throw new AssertionError(iuId + " is " + iu.getVersion() + " in the profile, expected " + version);
        }
        String root = profile.getInstallableUnitProperty(iu, IProfile.PROP_PROFILE_ROOT_IU);
        String symbolicName = require(BUNDLE);
        Bundle bundle = null;
        for (Bundle b : context.getBundles()) {
            if (b.getSymbolicName() != null && b.getSymbolicName().equals(symbolicName)) {
                bundle = b;
            }
        }
        if (bundle == null) {
            throw new AssertionError("bundle " + symbolicName + " is not installed in this runtime");
        }
        if ((bundle.getState() & (Bundle.RESOLVED | Bundle.STARTING | Bundle.ACTIVE)) == 0) {
            throw new AssertionError("bundle " + symbolicName + " is not resolved (state " + bundle.getState() + ")");
        }
        if (bundleVersion != null && !bundle.getVersion().equals(Version.parseVersion(bundleVersion))) {
            throw new AssertionError("bundle " + symbolicName + " is " + bundle.getVersion() + ", expected "
                    + bundleVersion);
        }
        ok(version == null ? "verify" : "verifyupdate", iuId + " " + iu.getVersion() + " in profile "
                + profile.getProfileId() + " (root=" + root + "); bundle " + symbolicName + " " + bundle.getVersion()
                + " " + stateName(bundle.getState()));
    }

    private void noUpdate() throws Exception {
        runCommand("org.eclipse.equinox.p2.ui.sdk.update");
        // a message dialog whose text is a Label, or a Link when it offers "Configure available software sites"
        Predicate<Control> noUpdates = c -> (c instanceof Label l && l.getText().contains("No updates"))
                || (c instanceof Link k && k.getText().contains("No updates"));
        Shell dialog = await("the 'no updates' answer", () -> shellWith(s -> first(s, Control.class, noUpdates)
                != null));
        String text = ui(() -> {
            Control c = first(dialog, Control.class, noUpdates);
            return c instanceof Label l ? l.getText() : ((Link) c).getText();
        });
        press(dialog, "OK");
        await("the dialog to close", () -> ui(() -> dialog.isDisposed()));
        ok("noupdate", "'" + text.replace('\n', ' ') + "'");
    }

    private void addSite() throws Exception {
        URI site = URI.create(require(SITE2));
        ProvisioningUI ui = ProvisioningUI.getDefaultUI();
        // what Preferences > Install/Update > Available Software Sites > Add... does
        ui.getRepositoryTracker().addRepository(site, "Sabot update site (rebuilt)", ui.getSession());
        ok("addsite", site.toString());
    }

    private void update() throws Exception {
        String featureIu = require(FEATURE) + ".feature.group";
        String version = require(VERSION);
        runCommand("org.eclipse.equinox.p2.ui.sdk.update");
        Shell wizard = await("the Available Updates wizard", () -> shellWith(s -> first(s, Tree.class,
                t -> (t.getStyle() & SWT.CHECK) != 0) != null || first(s, Table.class,
                        t -> (t.getStyle() & SWT.CHECK) != 0) != null));
        String listed = await(featureIu + " " + version + " listed", () -> ui(() -> {
            for (Widget item : items(wizard)) {
                IInstallableUnit iu = Adapters.adapt(item.getData(), IInstallableUnit.class);
                if (iu != null && iu.getId().equals(featureIu) && iu.getVersion().toString().equals(version)) {
                    return text(item);
                }
            }
            return null;
        }));
        String shot = ui(() -> shot(wizard, "p2-update.png"));
        finishWizard(wizard, null);
        String trusted = trust();
        markDone("update");
        ok("update", "listed '" + listed + "', trusted " + trusted + shot + "; Restart Now");
        restartNow();
    }

    private void exit() throws Exception {
        ok("exit", "closing the workbench");
        display.asyncExec(() -> PlatformUI.getWorkbench().close());
    }

    // --- wizard and dialogs -------------------------------------------------------------------------------------

    /**
     * Next until Finish is enabled on a page past the first (p2 resolves the plan on the details page), accepting
     * licences on the way, then Finish.
     */
    private void finishWizard(Shell wizard, String detailsTitle) throws Exception {
        await("the wizard to finish", () -> ui(() -> {
            if (wizard.isDisposed()) {
                return true;
            }
            Button accept = first(wizard, Button.class, b -> (b.getStyle() & SWT.RADIO) != 0 && b.isVisible()
                    && plain(b.getText()).startsWith("I accept"));
            if (accept != null && !accept.getSelection()) {
                accept.setSelection(true);
                accept.notifyListeners(SWT.Selection, new Event());
                return null;
            }
            Button next = button(wizard, "Next >");
            Button finish = button(wizard, "Finish");
            boolean firstPage = next != null && next.isEnabled() && first(wizard, Combo.class, Control::isVisible)
                    != null;
            if (finish != null && finish.isEnabled() && !firstPage) {
                display.asyncExec(() -> finish.notifyListeners(SWT.Selection, new Event()));
                return true;
            }
            if (next != null && next.isEnabled()) {
                display.asyncExec(() -> next.notifyListeners(SWT.Selection, new Event()));
            }
            return null;
        }));
        await("the wizard to close", () -> ui(() -> wizard.isDisposed()));
    }

    /** The "Trust Artifacts" dialog for unsigned content: every row checked, Trust Selected. */
    private String trust() throws Exception {
        Shell dialog = await("the trust dialog", () -> shellWith(s -> button(s, "Trust Selected") != null));
        String rows = ui(() -> {
            List<String> names = new ArrayList<>();
            for (Widget item : items(dialog)) {
                if (item instanceof TableItem t) {
                    t.setChecked(true);
                    Event e = new Event();
                    e.item = t;
                    e.detail = SWT.CHECK;
                    t.getParent().notifyListeners(SWT.Selection, e);
                } else if (item instanceof TreeItem t) {
                    t.setChecked(true);
                    Event e = new Event();
                    e.item = t;
                    e.detail = SWT.CHECK;
                    t.getParent().notifyListeners(SWT.Selection, e);
                }
                names.add(text(item));
            }
            return names.toString();
        });
        await("Trust Selected to be enabled", () -> ui(() -> button(dialog, "Trust Selected").isEnabled()));
        String shot = ui(() -> shot(dialog, "p2-trust.png"));
        press(dialog, "Trust Selected");
        return rows + shot;
    }

    /** Answers the p2 restart question with Restart Now: the workbench exits with 23, the start script relaunches. */
    private void restartNow() throws Exception {
        Shell dialog = await("the restart question", () -> shellWith(s -> button(s, "Restart Now") != null));
        press(dialog, "Restart Now");
    }

    private void runCommand(String id) {
        display.asyncExec(() -> {
            try {
                IWorkbenchWindow w = PlatformUI.getWorkbench().getActiveWorkbenchWindow();
                w.getService(IHandlerService.class).executeCommand(id, null);
            } catch (Exception e) {
                fail("command " + id, e);
            }
        });
    }

    private void press(Shell shell, String text) throws Exception {
        ui(() -> {
            Button b = button(shell, text);
            if (b == null) {
                throw new AssertionError("no button '" + text + "'");
            }
            display.asyncExec(() -> b.notifyListeners(SWT.Selection, new Event()));
            return null;
        });
    }

    // --- widgets ------------------------------------------------------------------------------------------------

    /** The open shells with their titles and label texts, for a failure message. */
    private String describeShells() {
        try {
            return ui(() -> {
                List<String> out = new ArrayList<>();
                for (Shell s : display.getShells()) {
                    if (s.isDisposed() || !s.isVisible()) {
                        continue;
                    }
                    List<String> labels = new ArrayList<>();
                    collectTexts(s, labels);
                    out.add("'" + s.getText() + "' " + labels);
                }
                return out.toString();
            });
        } catch (Exception e) {
            return "(shells unknown: " + e + ")";
        }
    }

    private static void collectTexts(Composite root, List<String> out) {
        for (Control c : root.getChildren()) {
            if (c instanceof Label l && !l.getText().isBlank()) {
                out.add(l.getText().replace('\n', ' '));
            } else if (c instanceof Button b && !b.getText().isBlank()) {
                out.add("[" + plain(b.getText()) + "]");
            } else if (c instanceof Link k && !k.getText().isBlank()) {
                out.add(k.getText().replace('\n', ' '));
            } else if (c instanceof org.eclipse.swt.widgets.Text t && !t.getText().isBlank()) {
                out.add(t.getText().replace('\n', ' '));
            }
            if (c instanceof Composite comp) {
                collectTexts(comp, out);
            }
        }
    }

    private Shell shellWith(Predicate<Shell> test) throws Exception {
        return ui(() -> {
            for (Shell s : display.getShells()) {
                if (!s.isDisposed() && s.isVisible() && test.test(s)) {
                    return s;
                }
            }
            return null;
        });
    }

    private static Button button(Composite root, String text) {
        return first(root, Button.class, b -> (b.getStyle() & SWT.PUSH) != 0 && b.isVisible()
                && plain(b.getText()).equals(text));
    }

    private static <T extends Control> T first(Composite root, Class<T> type, Predicate<T> test) {
        for (Control c : root.getChildren()) {
            if (type.isInstance(c) && test.test(type.cast(c))) {
                return type.cast(c);
            }
            if (c instanceof Composite comp) {
                T t = first(comp, type, test);
                if (t != null) {
                    return t;
                }
            }
        }
        return null;
    }

    /** Every tree item and table item under root, depth first. */
    private static List<Widget> items(Composite root) {
        List<Widget> out = new ArrayList<>();
        for (Control c : root.getChildren()) {
            if (c instanceof Tree tree) {
                for (TreeItem i : tree.getItems()) {
                    addTree(i, out);
                }
            } else if (c instanceof Table table) {
                out.addAll(Arrays.asList(table.getItems()));
            } else if (c instanceof Composite comp) {
                out.addAll(items(comp));
            }
        }
        return out;
    }

    private static void addTree(TreeItem item, List<Widget> out) {
        out.add(item);
        for (TreeItem child : item.getItems()) {
            addTree(child, out);
        }
    }

    private static String text(Widget item) {
        if (item instanceof TreeItem t) {
            int n = Math.max(1, t.getParent().getColumnCount());
            List<String> cols = new ArrayList<>();
            for (int i = 0; i < n; i++) {
                cols.add(t.getText(i));
            }
            return String.join(" | ", cols);
        }
        if (item instanceof TableItem t) {
            int n = Math.max(1, t.getParent().getColumnCount());
            List<String> cols = new ArrayList<>();
            for (int i = 0; i < n; i++) {
                cols.add(t.getText(i));
            }
            return String.join(" | ", cols);
        }
        return item.toString();
    }

    /** Menu and button text without mnemonics and accelerators. */
    private static String plain(String text) {
        int tab = text.indexOf('\t');
        return (tab >= 0 ? text.substring(0, tab) : text).replace("&", "");
    }

    /** Saves what the screen shows of a shell as PNG (no window manager under Xvfb: no title bar); "" without SHOTS. */
    private String shot(Shell shell, String name) {
        if (shots == null) {
            return "";
        }
        display.update();
        Rectangle b = shell.getBounds();
        Image image = new Image(display, b.width, b.height);
        GC gc = new GC(display);
        try {
            gc.copyArea(image, b.x, b.y);
            ImageLoader loader = new ImageLoader();
            loader.data = new ImageData[] {image.getImageData()};
            Files.createDirectories(shots);
            loader.save(shots.resolve(name).toString(), SWT.IMAGE_PNG);
        } catch (IOException e) {
            throw new IllegalStateException("screenshot " + name, e);
        } finally {
            gc.dispose();
            image.dispose();
        }
        return ", screenshot " + name;
    }

    // --- plumbing -----------------------------------------------------------------------------------------------

    private static Display findDisplay() {
        for (Thread t : Thread.getAllStackTraces().keySet()) {
            Display d = Display.findDisplay(t);
            if (d != null) {
                return d;
            }
        }
        return null;
    }

    /**
     * syncExec on a display that may still be in its constructor (findDisplay sees it as soon as it is registered,
     * before its locks exist: syncExec then throws a NullPointerException); retried until it is complete.
     */
    private void syncExecOnceCreated(Runnable r) {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(WAIT_S);
        while (true) {
            try {
                display.syncExec(r);
                return;
            } catch (NullPointerException constructing) {
                if (System.nanoTime() > deadline) {
                    throw constructing;
                }
                LockSupport.parkNanos(TimeUnit.MILLISECONDS.toNanos(PROBE_MS));
            }
        }
    }

    private <T> T ui(Callable<T> call) throws Exception {
        AtomicReference<T> result = new AtomicReference<>();
        AtomicReference<Throwable> error = new AtomicReference<>();
        display.syncExec(() -> {
            try {
                result.set(call.call());
            } catch (Throwable t) {
                error.set(t);
            }
        });
        if (error.get() instanceof Exception e) {
            throw e;
        }
        if (error.get() instanceof Error e) {
            throw e;
        }
        return result.get();
    }

    /** Probes until it gives a non-null value other than FALSE; fails after {@value #WAIT_S} s. */
    private <T> T await(String what, Callable<T> probe) throws Exception {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(WAIT_S);
        while (true) {
            T value = probe.call();
            if (value != null && !Boolean.FALSE.equals(value)) {
                return value;
            }
            if (System.nanoTime() > deadline) {
                throw new AssertionError("waited " + WAIT_S + " s for " + what + "; open shells: "
                        + (display == null ? "(no display)" : describeShells()));
            }
            LockSupport.parkNanos(TimeUnit.MILLISECONDS.toNanos(PROBE_MS));
            if (Thread.currentThread().isInterrupted()) {
                throw new InterruptedException("waiting for " + what);
            }
        }
    }

    private Set<String> done() throws IOException {
        return Files.exists(state) ? new LinkedHashSet<>(Files.readAllLines(state)) : new LinkedHashSet<>();
    }

    private synchronized void markDone(String step) throws IOException {
        Files.writeString(state, step + "\n", StandardCharsets.UTF_8, StandardOpenOption.CREATE,
                StandardOpenOption.APPEND);
    }

    private static String require(String property) {
        String v = System.getProperty(property);
        if (v == null || v.isBlank()) {
            throw new IllegalStateException("system property " + property + " is not set");
        }
        return v;
    }

    private static String stateName(int state) {
        return switch (state) {
            case Bundle.RESOLVED -> "RESOLVED";
            case Bundle.STARTING -> "STARTING";
            case Bundle.ACTIVE -> "ACTIVE";
            default -> "state " + state;
        };
    }

    private static void ok(String step, String detail) {
        System.out.println("UIDRIVER " + step + " ok: " + detail);
        System.out.flush();
    }

    private static void fail(String step, Throwable t) {
        System.out.println("UIDRIVER FAILED " + step + ": " + t);
        t.printStackTrace(System.out);
        System.out.flush();
        Runtime.getRuntime().halt(FAILED_EXIT);
    }
}
