package sabot.workbench.views;

import java.util.ArrayList;
import java.util.List;
import java.util.Objects;

import org.eclipse.swt.widgets.Display;

import sabot.workbench.fleet.RobotState;

/**
 * What waits for a robot to be drawn live ({@link WorkspaceView#whenDrawn}): each runs once, on the UI thread, after
 * the first paint whose live robots satisfy its condition. UI thread only.
 */
final class DrawnWaiters {

    private record Waiter(WorkspaceView.DrawnCondition condition, Runnable then) {
    }

    private final List<Waiter> waiters = new ArrayList<>();

    void add(WorkspaceView.DrawnCondition condition, Runnable then) {
        waiters.add(new Waiter(Objects.requireNonNull(condition), Objects.requireNonNull(then)));
    }

    /** A paint drew {@code live}: runs, after it has reached the screen, those whose condition one of them meets. */
    void painted(List<RobotState> live, Display display) {
        if (waiters.isEmpty()) {
            return;
        }
        for (Waiter w : List.copyOf(waiters)) {
            if (live.stream().anyMatch(w.condition()::holds)) {
                waiters.remove(w);
                display.asyncExec(w.then());
            }
        }
    }
}
