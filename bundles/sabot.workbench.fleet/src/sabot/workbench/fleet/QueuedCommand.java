package sabot.workbench.fleet;

import java.time.Instant;
import java.util.Objects;

/**
 * A command sent to a robot that was offline ({@link FleetState#goToWhenOnline}): stored at the server until the
 * robot comes online (docs/CONTROLML.md section 5), not answered yet. The robot judges it by its age when it arrives:
 * older than its stale limit, it is refused.
 *
 * @param robot    the robot's bare JID
 * @param id       the request's id
 * @param what     what it asks, for the operator (e.g. {@code go to (6.00, 4.40, 1.57 rad)})
 * @param queuedAt when it was sent (the workbench's clock)
 */
public record QueuedCommand(String robot, String id, String what, Instant queuedAt) {

    public QueuedCommand {
        Objects.requireNonNull(robot, "robot");
        Objects.requireNonNull(id, "id");
        Objects.requireNonNull(what, "what");
        Objects.requireNonNull(queuedAt, "queuedAt");
    }
}
