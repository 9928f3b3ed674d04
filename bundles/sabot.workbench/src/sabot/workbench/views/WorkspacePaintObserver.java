package sabot.workbench.views;

import java.util.List;

import org.osgi.annotation.versioning.ConsumerType;

import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotState;

/**
 * Told of every paint of the Workspace view's map, on the UI thread: for measurements (frame times, telemetry-to-screen
 * latency) made from outside the view. Registered as an OSGi service, every open Workspace view calls it; or added to
 * one view with {@link WorkspaceView#addPaintObserver}. Calls must return at once: they are part of the paint.
 */
@ConsumerType
public interface WorkspacePaintObserver {

    /** A paint begins (after the view found it has an area to paint). */
    default void paintStarting() {
    }

    /** A paint ended: its frame has been copied to the window. */
    void painted(Paint paint);

    /**
     * One paint of the map.
     *
     * @param startNanos {@link System#nanoTime()} when the paint began
     * @param endNanos   {@link System#nanoTime()} when its frame had been copied to the window
     * @param copyNanos  of the paint's duration, the frame's copy to the window (what the X server is sent), ns
     * @param robots     the robots the paint drew; never null
     * @param live       of them, those drawn live on the map (map shown, pose known, telemetry fresh); never null
     * @param fleet      the fleet service the robots came from, or null when none is bound
     */
    record Paint(long startNanos, long endNanos, long copyNanos, List<RobotState> robots, List<RobotState> live,
            FleetState fleet) {
    }
}
