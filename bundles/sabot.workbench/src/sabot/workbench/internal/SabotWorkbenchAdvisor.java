package sabot.workbench.internal;

import org.eclipse.ui.application.IWorkbenchConfigurer;
import org.eclipse.ui.application.IWorkbenchWindowConfigurer;
import org.eclipse.ui.application.WorkbenchAdvisor;
import org.eclipse.ui.application.WorkbenchWindowAdvisor;

final class SabotWorkbenchAdvisor extends WorkbenchAdvisor {

    private final LaunchOptions options;

    SabotWorkbenchAdvisor(LaunchOptions options) {
        this.options = options;
    }

    @Override
    public void initialize(IWorkbenchConfigurer configurer) {
        super.initialize(configurer);
        configurer.setSaveAndRestore(false); // the fleet layout is fixed; a stale saved layout would hide views
    }

    @Override
    public String getInitialWindowPerspectiveId() {
        return OperationPerspective.ID;
    }

    @Override
    public WorkbenchWindowAdvisor createWorkbenchWindowAdvisor(IWorkbenchWindowConfigurer configurer) {
        return new SabotWindowAdvisor(configurer, options);
    }
}
