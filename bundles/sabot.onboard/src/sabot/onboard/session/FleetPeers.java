package sabot.onboard.session;

import java.util.List;

import org.osgi.annotation.versioning.ProviderType;

import sabot.model.robot.PeerRobot;

/**
 * The other robots this one follows (roster rules 11 and 12, docs/CONTROLML.md): the members of the lab's robots'
 * group that the server vouches for, found in the fleet lobby or online in the roster, with the pose and velocity
 * their telemetry last gave. Provided by the {@code peers} task; the motion task puts them into its costmap and its
 * collision guard.
 *
 * @since 0.3
 */
@ProviderType
public interface FleetPeers {

    /**
     * @return the robots followed, as last heard (one entry per robot, none for a robot whose pose has not arrived
     *         yet); an immutable snapshot, cheap enough to read every control period
     */
    List<PeerRobot> peers();
}
