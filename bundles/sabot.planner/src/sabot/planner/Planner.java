package sabot.planner;

import java.util.List;

import org.osgi.annotation.versioning.ProviderType;

import sabot.model.geometry.Point2D;
import sabot.model.map.Costmap;

/**
 * Plans a path for the robot's centre over a costmap. Implementations are stateful (they keep their buffers between
 * requests so that re-planning allocates nothing) and not thread-safe: use one instance per thread. A planner that
 * runs helper threads ends them on {@link #close}.
 */
@ProviderType
public interface Planner extends AutoCloseable {

    /** @return a short name for logs and the command line, e.g. {@code lpn} */
    String name();

    /**
     * @param costmap the map to plan on; impassable: {@link Costmap#LETHAL}, {@link Costmap#INSCRIBED}, and
     *                {@link Costmap#NO_INFORMATION} unless the planner's {@link CostModel} allows unknown cells
     * @param start   map-frame position of the robot's centre, metres
     * @param goals   map-frame positions in metres; reaching the cell of any of them ends the path
     * @return a path from {@code start} to the goal whose cell is cheapest to reach, or the reason there is none
     */
    PlanResult plan(Costmap costmap, Point2D start, List<Point2D> goals);

    /** Plans to a single goal; see {@link #plan(Costmap, Point2D, List)}. */
    default PlanResult plan(Costmap costmap, Point2D start, Point2D goal) {
        return plan(costmap, start, List.of(goal));
    }

    /** Ends the planner's helper threads, if it has any; the planner must not be used afterwards. */
    @Override
    default void close() {
    }
}
