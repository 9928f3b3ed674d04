package sabot.workbench.fleet;

import org.osgi.annotation.versioning.ConsumerType;

/**
 * Observes a {@link FleetState}. Called on the fleet's own notification thread (never the UI thread), in the order
 * things happened; a listener must return quickly (a view marks itself dirty and redraws on its own clock).
 */
@ConsumerType
public interface FleetListener {

    /**
     * A robot was added or something of it changed (presence, a telemetry value, its path...).
     *
     * @param robot the robot's new state; never null
     */
    void robotChanged(RobotState robot);

    /**
     * A robot is no longer followed (removed from the roster or the configured list).
     *
     * @param jid its bare JID
     */
    default void robotRemoved(String jid) {
    }

    /** @param status the connection's new state; never null */
    default void connectionChanged(ConnectionStatus status) {
    }

    /**
     * The robots asking for access changed ({@link FleetState#accessRequests()}).
     *
     * @param robots their bare JIDs, sorted; empty when none
     */
    default void accessRequestsChanged(java.util.List<String> robots) {
    }

    /**
     * The commands waiting for offline robots changed ({@link FleetState#queuedCommands()}).
     *
     * @param queued oldest first; empty when none
     */
    default void queuedCommandsChanged(java.util.List<QueuedCommand> queued) {
    }
}
