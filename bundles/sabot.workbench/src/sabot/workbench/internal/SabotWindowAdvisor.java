package sabot.workbench.internal;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Arrays;
import java.util.stream.Collectors;

import org.eclipse.swt.SWT;
import org.eclipse.swt.graphics.GC;
import org.eclipse.swt.graphics.Image;
import org.eclipse.swt.graphics.ImageData;
import org.eclipse.swt.graphics.ImageLoader;
import org.eclipse.swt.graphics.Rectangle;
import org.eclipse.swt.widgets.Display;
import org.eclipse.swt.widgets.Shell;
import org.eclipse.swt.graphics.Point;
import org.eclipse.ui.PlatformUI;
import org.eclipse.ui.application.ActionBarAdvisor;
import org.eclipse.ui.application.IActionBarConfigurer;
import org.eclipse.ui.application.IWorkbenchWindowConfigurer;
import org.eclipse.ui.application.WorkbenchWindowAdvisor;
import org.eclipse.ui.views.IViewDescriptor;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.workbench.views.WorkspaceView;

final class SabotWindowAdvisor extends WorkbenchWindowAdvisor {

    private static final Logger LOG = LoggerFactory.getLogger("sabot.workbench");

    private final LaunchOptions options;

    SabotWindowAdvisor(IWorkbenchWindowConfigurer configurer, LaunchOptions options) {
        super(configurer);
        this.options = options;
    }

    @Override
    public ActionBarAdvisor createActionBarAdvisor(IActionBarConfigurer configurer) {
        return new SabotActionBarAdvisor(configurer);
    }

    @Override
    public void preWindowOpen() {
        IWorkbenchWindowConfigurer c = getWindowConfigurer();
        c.setInitialSize(new Point(1280, 800));
        c.setShowMenuBar(true);
        c.setShowCoolBar(true); // Stop All Robots
        c.setShowStatusLine(true);
        c.setTitle("Sabot Workbench");
    }

    /**
     * @return the names of the Sabot views this installation has, sorted, e.g. {@code Fleet, Joystick, Workspace}: the
     *         core's and those of the plug-ins installed (Window › Show View lists them)
     */
    static String sabotViews() {
        return Arrays.stream(PlatformUI.getWorkbench().getViewRegistry().getViews()).filter(v -> v.getId()
                .startsWith("sabot.")).map(IViewDescriptor::getLabel).sorted().collect(Collectors.joining(", "));
    }

    @Override
    public void postWindowOpen() {
        Shell shell = getWindowConfigurer().getWindow().getShell();
        LOG.info("Sabot Workbench window open ({}x{}); views: {}", shell.getSize().x, shell.getSize().y,
                sabotViews());
        if (options.screenshot() == null && !options.exitAfterStartup()) {
            return;
        }
        Display display = shell.getDisplay();
        LaunchOptions.Wait wait = options.waitFor();
        if (wait == LaunchOptions.Wait.NONE) {
            capture(shell, display);
            return;
        }
        org.eclipse.ui.IWorkbenchPage page = getWindowConfigurer().getWindow().getActivePage();
        WorkspaceView workspace = page == null ? null : (WorkspaceView) page.findView(WorkspaceView.ID);
        if (workspace == null) {
            LOG.warn("no Workspace view to wait on; screenshot taken at once");
            capture(shell, display);
            return;
        }
        // the paints decide (each telemetry update repaints the map); the timer is only the deadline
        boolean[] taken = { false };
        Runnable once = () -> {
            if (!taken[0]) {
                taken[0] = true;
                capture(shell, display);
            }
        };
        WorkspaceView.DrawnCondition condition = wait == LaunchOptions.Wait.MISSION ? WorkspaceView::showsRunningMission
                : r -> true;
        workspace.whenDrawn(condition, () -> {
            LOG.info("screenshot: {} on the map", wait == LaunchOptions.Wait.MISSION
                    ? "a running mission (path and trail)" : "a live robot");
            once.run();
        });
        display.timerExec(LaunchOptions.LIVE_WAIT_S * 1000, () -> {
            if (!taken[0]) {
                LOG.warn("no {} on the map within {} s; screenshot taken anyway", wait == LaunchOptions.Wait.MISSION
                        ? "running mission" : "live robot", LaunchOptions.LIVE_WAIT_S);
                once.run();
            }
        });
    }

    private void capture(Shell shell, Display display) {
        // Queued behind the events of the first layout and paint, so the capture shows the drawn window.
        display.asyncExec(() -> display.asyncExec(() -> {
            if (options.screenshot() != null && !shell.isDisposed()) {
                shell.update();
                try {
                    saveScreenshot(shell, options.screenshot());
                    LOG.info("screenshot saved to {}", options.screenshot());
                } catch (IOException e) {
                    LOG.error("screenshot failed: {}", e.getMessage());
                }
            }
            if (options.exitAfterStartup()) {
                PlatformUI.getWorkbench().close();
            }
        }));
    }

    /** Saves what the display shows of a shell (a real screen grab) as PNG. */
    static void saveScreenshot(Shell shell, Path file) throws IOException {
        // From the top of the shell (menu bar) to the bottom of its client area (status line): without a window
        // manager the shell's bounds also count trim below it that nothing draws.
        Rectangle bounds = shell.getBounds();
        Rectangle client = shell.getClientArea();
        Point clientOrigin = shell.toDisplay(client.x, client.y);
        int height = Math.min(bounds.height, clientOrigin.y - bounds.y + client.height);
        Display display = shell.getDisplay();
        Image image = new Image(display, bounds.width, height);
        GC gc = new GC(display);
        try {
            gc.copyArea(image, bounds.x, bounds.y);
            ImageData data = image.getImageData();
            ImageLoader loader = new ImageLoader();
            loader.data = new ImageData[] { data };
            Files.createDirectories(file.toAbsolutePath().getParent());
            loader.save(file.toString(), SWT.IMAGE_PNG);
        } catch (org.eclipse.swt.SWTException e) {
            throw new IOException("cannot capture or write " + file + ": " + e.getMessage(), e);
        } finally {
            gc.dispose();
            image.dispose();
        }
    }
}
