package sabot.model.robot;

import java.time.Instant;
import java.util.Objects;

/**
 * A robot's claim on a narrow passage of the map (docs/PASSAGES.md): it waits for its turn, or it passes. Robots tell
 * each other their claims ({@code cm.passage}); the earliest request goes first. Immutable.
 *
 * @param passage the passage's id on the map ({@link sabot.model.map.Passage#id()}), from 1
 * @param state   waiting for its turn, or passing
 * @param since   when the robot asked for the passage (its request's time, which orders the robots waiting; kept when
 *                it starts passing), on its own clock; never null
 */
public record PassageClaim(int passage, State state, Instant since) {

    /** What the robot does about the passage. */
    public enum State {
        /** It stands (or is about to stop) short of the passage until its turn comes. */
        WAITING,
        /** It has the passage: it drives through it, and no other robot enters until it has left. */
        PASSING
    }

    public PassageClaim {
        if (passage < 1) {
            throw new IllegalArgumentException("passage id must be >= 1, got " + passage);
        }
        Objects.requireNonNull(state, "state");
        Objects.requireNonNull(since, "since");
    }

    /** @return whether this claim's request came before {@code other}'s: earlier, or at once and by a smaller JID */
    public static boolean before(PassageClaim a, String aJid, PassageClaim b, String bJid) {
        int c = a.since().compareTo(b.since());
        return c < 0 || (c == 0 && aJid.compareTo(bJid) < 0);
    }
}
