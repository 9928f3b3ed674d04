package sabot.onboard.controlml.internal.peers;

import java.time.Clock;
import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Set;
import java.util.TreeMap;

import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.robot.PassageClaim;
import sabot.model.robot.PeerRobot;

/**
 * What this robot last heard of each robot it follows: plain Java, no XMPP. The {@code peers} task says which robots
 * are followed and whether they are online; their telemetry comes in on Smack's listener thread. Every change makes a
 * new immutable snapshot, so that {@link #peers} is one volatile read for the control loop.
 * <p>
 * Telemetry of a robot not followed is dropped (an item still on its way after the robot left the group, or one the
 * server delivers for a subscription this robot never asked for). A robot appears in the snapshot once its first pose
 * has arrived, with a zero velocity until its first {@code cm.velocity} and no passage claim until its first
 * {@code cm.passage} says one; it stays, marked offline, when it goes offline, and disappears only when it is no longer
 * followed.
 */
final class PeerBook {

    /** One followed robot. Guarded by the book. */
    private static final class Entry {
        Pose2D pose;
        Twist2D velocity = Twist2D.ZERO;
        Instant heard;
        boolean online = true;
        /** Its claim on a narrow passage, null for none. */
        PassageClaim passage;
    }

    private final Clock clock;
    /** By bare JID, sorted: the snapshot's order. Guarded by this. */
    private final Map<String, Entry> entries = new TreeMap<>();
    private volatile List<PeerRobot> snapshot = List.of();

    /** @param clock this robot's clock, which stamps each pose when it arrives */
    PeerBook(Clock clock) {
        this.clock = Objects.requireNonNull(clock, "clock");
    }

    /** @return the followed robots whose pose has arrived, as last heard; an immutable snapshot */
    List<PeerRobot> peers() {
        return snapshot;
    }

    /** Starts following a robot (online, nothing heard yet); nothing when it is followed already. */
    synchronized void follow(String jid) {
        entries.putIfAbsent(Objects.requireNonNull(jid, "jid"), new Entry());
    }

    /** Stops following a robot: its entry is forgotten. */
    synchronized void unfollow(String jid) {
        if (entries.remove(jid) != null) {
            publish();
        }
    }

    /** Forgets every robot (the task stops). */
    synchronized void clear() {
        entries.clear();
        publish();
    }

    /** @return the robots followed (bare JIDs), a copy */
    synchronized Set<String> followed() {
        return Set.copyOf(entries.keySet());
    }

    /** A followed robot's presence: online, or gone offline (its last pose is kept: its body is still there). */
    synchronized void online(String jid, boolean online) {
        Entry e = entries.get(jid);
        if (e != null && e.online != online) {
            e.online = online;
            if (e.pose != null) {
                publish();
            }
        }
    }

    /** A robot's pose arrived ({@code cm.position}): stamped with this robot's clock now. */
    void pose(String jid, Pose2D pose) {
        Objects.requireNonNull(pose, "pose");
        Instant now = clock.instant();
        synchronized (this) {
            Entry e = entries.get(jid);
            if (e == null) {
                return;
            }
            e.pose = pose;
            e.heard = now;
            publish();
        }
    }

    /** A robot's velocity arrived ({@code cm.velocity}). */
    synchronized void velocity(String jid, Twist2D velocity) {
        Objects.requireNonNull(velocity, "velocity");
        Entry e = entries.get(jid);
        if (e == null) {
            return;
        }
        e.velocity = velocity;
        if (e.pose != null) {
            publish();
        }
    }

    /** A robot's claim on a narrow passage arrived ({@code cm.passage}): null for none. */
    synchronized void passage(String jid, PassageClaim claim) {
        Entry e = entries.get(jid);
        if (e == null || Objects.equals(e.passage, claim)) {
            return;
        }
        e.passage = claim;
        if (e.pose != null) {
            publish();
        }
    }

    /** Makes the snapshot of the entries; the caller holds the lock. */
    private void publish() {
        List<PeerRobot> now = new ArrayList<>(entries.size());
        entries.forEach((jid, e) -> {
            if (e.pose != null) {
                now.add(new PeerRobot(jid, e.pose, e.velocity, e.heard, e.online, e.passage));
            }
        });
        snapshot = List.copyOf(now);
    }
}
