package sabot.workbench.diagnostics.internal;

import org.eclipse.jface.viewers.ArrayContentProvider;
import org.eclipse.jface.viewers.ColumnLabelProvider;
import org.eclipse.jface.viewers.TableViewer;
import org.eclipse.jface.viewers.TableViewerColumn;
import org.eclipse.swt.SWT;
import org.eclipse.swt.layout.GridData;
import org.eclipse.swt.layout.GridLayout;
import org.eclipse.swt.widgets.Composite;
import org.eclipse.swt.widgets.Label;
import org.eclipse.ui.part.ViewPart;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;

/** Diagnostics view: the Java runtime and the installed bundles with their states, for support requests. */
public final class DiagnosticsView extends ViewPart {

    private TableViewer viewer;

    @Override
    public void createPartControl(Composite parent) {
        BundleContext context = FrameworkUtil.getBundle(getClass()).getBundleContext();
        parent.setLayout(new GridLayout(1, false));
        Label summary = new Label(parent, SWT.NONE);
        summary.setText(RuntimeReport.summary(context));
        viewer = new TableViewer(parent, SWT.FULL_SELECTION | SWT.BORDER | SWT.V_SCROLL);
        viewer.getTable().setLayoutData(new GridData(SWT.FILL, SWT.FILL, true, true));
        viewer.getTable().setHeaderVisible(true);
        column("Id", 50, r -> Long.toString(r.id()));
        column("Bundle", 320, RuntimeReport.BundleRow::symbolicName);
        column("Version", 200, RuntimeReport.BundleRow::version);
        column("State", 100, RuntimeReport.BundleRow::state);
        viewer.setContentProvider(ArrayContentProvider.getInstance());
        viewer.setInput(RuntimeReport.bundles(context));
    }

    private void column(String title, int width, java.util.function.Function<RuntimeReport.BundleRow, String> text) {
        TableViewerColumn c = new TableViewerColumn(viewer, SWT.LEFT);
        c.getColumn().setText(title);
        c.getColumn().setWidth(width);
        c.setLabelProvider(new ColumnLabelProvider() {
            @Override
            public String getText(Object element) {
                return text.apply((RuntimeReport.BundleRow) element);
            }
        });
    }

    @Override
    public void setFocus() {
        viewer.getControl().setFocus();
    }
}
