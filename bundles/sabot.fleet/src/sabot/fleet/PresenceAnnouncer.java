package sabot.fleet;

import org.jivesoftware.smack.SmackException.NotConnectedException;
import org.jivesoftware.smack.XMPPConnection;

import sabot.controlml.PresenceLevel;
import sabot.controlml.payload.MissionState;

/**
 * A device's side of the presence levels: tell it the mission state and maintenance mode as they change, and it
 * sends a presence when (and only when) what subscribers see changes. Thread-safe.
 */
public final class PresenceAnnouncer {

    private final XMPPConnection connection;
    private MissionState mission = MissionState.IDLE;
    private boolean maintenance;
    private String announced;

    /** @param connection the device's connection */
    public PresenceAnnouncer(XMPPConnection connection) {
        this.connection = connection;
    }

    /** @return the current level */
    public synchronized PresenceLevel level() {
        return PresenceLevels.levelFor(mission, maintenance);
    }

    /** The mission state changed. @return true when a presence was sent */
    public synchronized boolean missionChanged(MissionState state) throws NotConnectedException, InterruptedException {
        this.mission = state;
        return announce();
    }

    /** Maintenance mode was switched. @return true when a presence was sent */
    public synchronized boolean maintenanceChanged(boolean on) throws NotConnectedException, InterruptedException {
        this.maintenance = on;
        return announce();
    }

    /** Sends the current presence if it differs from the last one sent. @return true when one was sent */
    public synchronized boolean announce() throws NotConnectedException, InterruptedException {
        String key = mission + "/" + maintenance;
        if (key.equals(announced)) {
            return false;
        }
        connection.sendStanza(PresenceLevels.presenceFor(connection, mission, maintenance));
        announced = key;
        return true;
    }
}
