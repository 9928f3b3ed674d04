package sabot.controlml.payload;

import java.time.Instant;
import java.util.List;
import java.util.Objects;

/**
 * {@code cm.trajectory}: the planned (get) or imposed (set) timed path.
 *
 * @param start  the time of {@code t = 0}; never null
 * @param points samples with non-decreasing {@code t}; never null
 */
public record Trajectory(Instant start, List<TrajectoryPoint> points) {
    public Trajectory {
        Objects.requireNonNull(start, "start");
        points = List.copyOf(points);
    }
}
