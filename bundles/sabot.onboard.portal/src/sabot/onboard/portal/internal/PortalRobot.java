package sabot.onboard.portal.internal;

import java.io.IOException;
import java.util.Map;
import java.util.Optional;

import sabot.controlml.Role;
import sabot.controlml.payload.GridMap;
import sabot.onboard.config.OnboardSettings;

/** What the page asks of the robot: the task wires it to the robot's services ({@link PortalTask}). */
interface PortalRobot {

    /** @return the robot's state for the status page (a JSON object's members); never null */
    Map<String, Object> robotState();

    /** @return the map the planner uses, or empty when the motion task does not run */
    Optional<GridMap> map();

    /** @return the robot's QR inventory (the vCard photo it published) as PNG, or empty when not available */
    Optional<byte[]> inventoryQr();

    /**
     * @return the account's role on this robot, by the same access rules as ControlML requests; {@link Role#NONE}
     *         when it has none
     */
    Role roleOf(String account);

    /** @see sabot.onboard.session.RobotSession#checkPassword */
    boolean checkPassword(String account, String password) throws IOException;

    /** @return the configuration file's service */
    OnboardSettings settings();
}
