package sabot.workbench.views;

import java.util.function.BiConsumer;
import java.util.function.Consumer;

import org.eclipse.swt.widgets.Control;

import sabot.controlml.payload.GridMap;
import sabot.workbench.fleet.Availability;
import sabot.workbench.fleet.FleetBinding;
import sabot.workbench.fleet.FleetCommandException;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotState;

/**
 * The Workspace's map: fetched from the first robot online (robots of one lab share it), off the UI thread, once; a
 * failed fetch is asked again with the next change of the fleet. UI thread.
 */
final class MapFetch {

    private final FleetBinding fleet;
    private final Control control;
    private final BiConsumer<GridMap, String> shown;
    private final Consumer<String> failed;
    private boolean requested;

    /**
     * @param control the view's control: the answer comes on its display, and nothing once it is disposed
     * @param shown   takes the map and the JID of the robot it came from
     * @param failed  takes the reason for the operator
     */
    MapFetch(FleetBinding fleet, Control control, BiConsumer<GridMap, String> shown,
            Consumer<String> failed) {
        this.fleet = fleet;
        this.control = control;
        this.shown = shown;
        this.failed = failed;
    }

    /** Asks for the map unless it has been asked for already (or a robot to ask is missing). */
    void request() {
        if (requested) {
            return;
        }
        FleetState f = fleet.fleet();
        RobotState source = fleet.robots().stream().filter(r -> r.availability() != Availability.OFFLINE).findFirst()
                .orElse(null);
        if (f == null || source == null) {
            return;
        }
        requested = true;
        f.map(source.jid()).whenComplete((m, e) -> control.getDisplay().asyncExec(() -> {
            if (control.isDisposed()) {
                return;
            }
            if (m != null) {
                shown.accept(m, source.jid());
            } else {
                requested = false; // asked again with the next change
                failed.accept("map of " + source.name() + ": " + describe(e));
            }
        }));
    }

    private static String describe(Throwable e) {
        FleetCommandException f = FleetCommandException.in(e);
        return f != null ? f.text() + " (" + f.condition().element() + ")" : String.valueOf(e);
    }
}
