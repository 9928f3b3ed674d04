package sabot.fleet;

import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.packet.Presence;

import sabot.controlml.PresenceLevel;
import sabot.controlml.PresenceLevelElement;
import sabot.controlml.payload.MissionState;

/**
 * The presence-level rules: maintenance mode is {@link PresenceLevel#AWAY}; a running or paused mission is
 * {@link PresenceLevel#BUSY}; otherwise {@link PresenceLevel#FREE}.
 */
public final class PresenceLevels {

    private PresenceLevels() {
    }

    /** @return the level of a device in this state */
    public static PresenceLevel levelFor(MissionState mission, boolean maintenance) {
        if (maintenance) {
            return PresenceLevel.AWAY;
        }
        return mission.isActive() ? PresenceLevel.BUSY : PresenceLevel.FREE;
    }

    /**
     * @return the available presence announcing a state: show from the level, a status text for generic clients,
     *         and the {@link PresenceLevelElement}
     */
    public static Presence presenceFor(XMPPConnection connection, MissionState mission, boolean maintenance) {
        PresenceLevel level = levelFor(mission, maintenance);
        String status = switch (level) {
            case FREE -> "free";
            case BUSY -> "busy: mission " + mission.code();
            case AWAY -> "away: maintenance";
        };
        return connection.getStanzaFactory().buildPresenceStanza().ofType(Presence.Type.available).setMode(level
                .mode()).setStatus(status).addExtension(new PresenceLevelElement(level, mission.code(), maintenance))
                .build();
    }

    /**
     * @return the level a presence shows: its {@link PresenceLevelElement} when readable, else its show; null for an
     *         unavailable presence
     */
    public static PresenceLevel of(Presence presence) {
        if (!presence.isAvailable()) {
            return null;
        }
        PresenceLevelElement e = PresenceLevelElement.from(presence);
        return e != null && e.level() != null ? e.level() : PresenceLevel.fromMode(presence);
    }
}
