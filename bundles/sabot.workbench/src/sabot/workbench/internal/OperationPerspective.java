package sabot.workbench.internal;

import java.util.List;

import org.eclipse.ui.IPageLayout;
import org.eclipse.ui.IPerspectiveFactory;
import org.eclipse.ui.IPlaceholderFolderLayout;

import sabot.workbench.views.FleetView;
import sabot.workbench.views.WorkspaceView;

/**
 * The operator's layout, the product's default perspective ("Operation"): the workspace map in the centre, the fleet
 * table below it, no editor area, and on the right a folder where the optional plug-ins' views land when they are
 * installed and opened (placeholders: a view that is not installed takes no room).
 */
public final class OperationPerspective implements IPerspectiveFactory {

    /** Kept from the first release: the plug-ins' perspective extensions name it. */
    public static final String ID = "sabot.workbench.perspective";
    /** The folder of the plug-ins' views, right of the workspace. */
    public static final String PLUGIN_FOLDER = "sabot.workbench.folder.plugins";
    /**
     * The plug-ins' views (their own bundles declare them; the core cannot depend on optional bundles, so their ids
     * are named here, each plug-in's {@code ID} constant).
     */
    static final List<String> PLUGIN_VIEWS = List.of("sabot.workbench.joystick.view", "sabot.workbench.pid.view",
            "sabot.workbench.remotefs.view", "sabot.workbench.identity.view", "sabot.workbench.diagnostics.view",
            "sabot.workbench.statistics.view");

    @Override
    public void createInitialLayout(IPageLayout layout) {
        layout.setEditorAreaVisible(false);
        layout.addView(WorkspaceView.ID, IPageLayout.TOP, 0.72f, layout.getEditorArea());
        layout.addView(FleetView.ID, IPageLayout.BOTTOM, 0.72f, WorkspaceView.ID);
        IPlaceholderFolderLayout plugins = layout.createPlaceholderFolder(PLUGIN_FOLDER, IPageLayout.RIGHT, 0.64f,
                WorkspaceView.ID);
        for (String view : PLUGIN_VIEWS) {
            plugins.addPlaceholder(view);
        }
        layout.addShowViewShortcut(WorkspaceView.ID);
        layout.addShowViewShortcut(FleetView.ID);
        layout.getViewLayout(WorkspaceView.ID).setCloseable(false); // the core: the map is always there
    }
}
