package sabot.controlml;

import java.util.Locale;

import org.jivesoftware.smack.packet.Presence;

/**
 * A device's availability for new work, as operators see it in their rosters. It rides on XMPP presence: an
 * {@code available} presence whose {@code show} is the level's {@link #mode()}, a status text, and a
 * {@link PresenceLevelElement} saying the level exactly (clients that ignore the extension still see the show).
 */
public enum PresenceLevel {
    /** idle and accepting missions: {@code show} absent (available) */
    FREE(Presence.Mode.available),
    /** executing a mission: {@code show = dnd} */
    BUSY(Presence.Mode.dnd),
    /** in maintenance (or otherwise not taking missions): {@code show = away} */
    AWAY(Presence.Mode.away);

    private final Presence.Mode mode;

    PresenceLevel(Presence.Mode mode) {
        this.mode = mode;
    }

    /** @return the XMPP presence mode ({@code show}) this level is shown as */
    public Presence.Mode mode() {
        return mode;
    }

    /** @return the attribute value, e.g. {@code busy} */
    public String attribute() {
        return name().toLowerCase(Locale.ROOT);
    }

    /** @return the level for an attribute value, or null */
    public static PresenceLevel fromAttribute(String value) {
        for (PresenceLevel l : values()) {
            if (l.attribute().equals(value)) {
                return l;
            }
        }
        return null;
    }

    /**
     * The level a presence shows when it carries no {@link PresenceLevelElement}: dnd is busy, away/xa is away,
     * anything else available is free.
     *
     * @return the level, or null for an unavailable presence
     */
    public static PresenceLevel fromMode(Presence presence) {
        if (!presence.isAvailable()) {
            return null;
        }
        return switch (presence.getMode()) {
            case dnd -> BUSY;
            case away, xa -> AWAY;
            default -> FREE;
        };
    }
}
