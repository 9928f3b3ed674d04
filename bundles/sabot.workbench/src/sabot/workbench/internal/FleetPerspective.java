package sabot.workbench.internal;

import org.eclipse.ui.IPageLayout;
import org.eclipse.ui.IPerspectiveFactory;

import sabot.workbench.views.FleetView;
import sabot.workbench.views.WorkspaceView;

/** The operator's layout: the workspace map on top, the fleet table below, no editor area. */
public final class FleetPerspective implements IPerspectiveFactory {

    public static final String ID = "sabot.workbench.perspective";

    @Override
    public void createInitialLayout(IPageLayout layout) {
        layout.setEditorAreaVisible(false);
        layout.addView(WorkspaceView.ID, IPageLayout.TOP, 0.72f, layout.getEditorArea());
        layout.addView(FleetView.ID, IPageLayout.BOTTOM, 0.72f, WorkspaceView.ID);
    }
}
