package sabot.onboard.motion.loop;

import java.time.Duration;
import java.time.Instant;
import java.util.List;
import java.util.Locale;

import sabot.model.geometry.Pose2D;
import sabot.model.map.Passage;
import sabot.model.path.Trajectory;
import sabot.model.path.TrajectorySample;
import sabot.model.robot.PassageClaim;
import sabot.model.robot.PeerRobot;

/**
 * The rule of narrow passages (docs/PASSAGES.md): one robot at a time in a passage of the map, the earliest request
 * first. A robot whose path ahead enters a passage within {@code approach} metres asks for it (a {@code WAITING}
 * claim stamped with the time of its request, which it tells the other robots as {@code cm.passage}); it takes it (its
 * claim turns {@code PASSING}) once its request has stood {@link #SETTLE} seconds and no other robot heard within the
 * peer memory passes there, asked for it earlier (ties: the smaller JID), or has its footprint in it; until then it
 * yields, stopped short of the passage (the request is made {@code approach} metres ahead, so that a robot on its
 * way drives on while it stands, with its braking distance to spare). It lets go when its footprint has left the passage and its path no longer
 * enters it, and when its mission ends.
 * <p>
 * Every robot judges by the same claims, so that two robots meeting at a door agree on who goes first; a claim
 * announced in the last {@link #SETTLE} seconds by the other may still be on its way, which is why a request waits
 * that long before it is taken. Used by the loop's thread only.
 */
final class PassageRule {

    /**
     * How long a request stands before the robot may take the passage, s: the other robots' claims made meanwhile
     * reach it first. Two periods of {@code cm.passage} at the peers task's 5 Hz lease and the server's delivery.
     */
    static final double SETTLE = 0.5;
    /** Step along the trajectory ahead at which it is checked against the passages, s. */
    private static final double STEP = 0.05;

    /** What the rule says for this period. */
    enum Kind {
        /** no passage ahead: drive on */
        NONE,
        /** the robot has the passage ahead or is in it: drive on */
        GO,
        /**
         * the robot has asked for the passage ahead and nobody goes first as far as it knows, but its request has not
         * stood {@link #SETTLE} seconds yet: a robot on its way drives on (it is still about the approach away, more
         * than its braking distance), one standing stays
         */
        ASKING,
        /** stop short of the passage and wait */
        YIELD
    }

    /** @param reason why it yields, for the operator ({@code sabot-02@sabot.local passes}); "" otherwise */
    record Verdict(Kind kind, Passage passage, String reason) {
        static final Verdict NONE = new Verdict(Kind.NONE, null, "");
    }

    private List<Passage> passages = List.of();
    private PassageClaim claim;

    /** Takes the map's passages (a new map: the claim is given up). */
    void passages(List<Passage> list) {
        passages = List.copyOf(list);
        claim = null;
    }

    List<Passage> passages() {
        return passages;
    }

    /** @return this robot's claim, or null for none */
    PassageClaim claim() {
        return claim;
    }

    /**
     * The robot drives no path (it settles on or waits at a target): a request ends, and so does the passage it held
     * once its footprint is out of it.
     */
    void lapse(Pose2D pose, double radius) {
        if (claim == null) {
            return;
        }
        Passage held = byId(claim.passage());
        if (claim.state() == PassageClaim.State.WAITING || held == null || !held.touches(pose.x(), pose.y(),
                radius)) {
            claim = null;
        }
    }

    /** Gives up the claim (the mission ended, was paused or failed). */
    void release() {
        claim = null;
    }

    /**
     * @param from     trajectory time from which to look, s
     * @param approach m of the path ahead looked at
     * @param radius   the robot's footprint radius, m
     * @return the passage the footprint is in now, else the first one the path ahead enters within {@code approach}
     *         metres, else null
     */
    Passage ahead(Pose2D pose, Trajectory trajectory, double from, double approach, double radius) {
        if (passages.isEmpty()) {
            return null;
        }
        for (Passage p : passages) {
            if (p.touches(pose.x(), pose.y(), radius)) {
                return p;
            }
        }
        if (trajectory == null) {
            return null;
        }
        // measured along the path from its point at `from` (where a robot that yields began to: it braked beyond it)
        TrajectorySample first = trajectory.sample(Math.min(from, trajectory.duration()));
        double travelled = 0;
        double px = first.x();
        double py = first.y();
        for (double s = from; s <= trajectory.duration() + STEP / 2 && travelled <= approach; s += STEP) {
            TrajectorySample r = trajectory.sample(Math.min(s, trajectory.duration()));
            travelled += Math.hypot(r.x() - px, r.y() - py);
            px = r.x();
            py = r.y();
            for (Passage p : passages) {
                if (p.touches(r.x(), r.y(), radius)) {
                    return p;
                }
            }
        }
        return null;
    }

    /**
     * Judges one period.
     *
     * @param self   this robot's bare JID (ties between requests at one instant go to the smaller)
     * @param ahead  {@link #ahead}'s passage, or null
     * @param pose   where the robot stands
     * @param radius the fleet's footprint radius, m
     * @param peers  the other robots as last heard
     * @param discs  their footprints now ({@link PeerField})
     * @param memory s a robot not heard from still counts
     */
    Verdict decide(Instant now, String self, Passage ahead, Pose2D pose, double radius, List<PeerRobot> peers,
            List<PeerField.Disc> discs, double memory) {
        if (claim != null && claim.state() == PassageClaim.State.PASSING) {
            Passage held = byId(claim.passage());
            if (held != null && (held.touches(pose.x(), pose.y(), radius) || (ahead != null && ahead.id() == held
                    .id()))) {
                return new Verdict(Kind.GO, held, "");
            }
            claim = null; // through it: let go
        }
        if (ahead == null) {
            claim = null;
            return Verdict.NONE;
        }
        if (claim == null || claim.passage() != ahead.id()) {
            claim = new PassageClaim(ahead.id(), PassageClaim.State.WAITING, now);
        }
        String blocker = blocker(now, self, ahead, peers, discs, memory);
        if (blocker != null) {
            return new Verdict(Kind.YIELD, ahead, blocker);
        }
        if (Duration.between(claim.since(), now).toNanos() * 1e-9 < SETTLE) {
            return new Verdict(Kind.ASKING, ahead, "asking the other robots");
        }
        claim = new PassageClaim(ahead.id(), PassageClaim.State.PASSING, claim.since());
        return new Verdict(Kind.GO, ahead, "");
    }

    /** @return why another robot goes first, or null when none does */
    private String blocker(Instant now, String self, Passage p, List<PeerRobot> peers, List<PeerField.Disc> discs,
            double memory) {
        for (PeerRobot peer : peers) {
            PassageClaim other = peer.passage();
            if (other == null || other.passage() != p.id() || Duration.between(peer.heard(), now).toNanos()
                    * 1e-9 > memory) {
                continue;
            }
            if (other.state() == PassageClaim.State.PASSING) {
                return peer.jid() + " passes";
            }
            if (PassageClaim.before(other, peer.jid(), claim, self)) {
                return peer.jid() + " asked first";
            }
        }
        for (PeerField.Disc d : discs) {
            if (p.touches(d.x(), d.y(), d.radius())) {
                return d.jid() + " is in it";
            }
        }
        return null;
    }

    private Passage byId(int id) {
        for (Passage p : passages) {
            if (p.id() == id) {
                return p;
            }
        }
        return null;
    }

    /** @return the passage's name for the log, e.g. {@code passage 1 (4.20..4.40, 1.70..2.70)} */
    static String describe(Passage p) {
        return String.format(Locale.ROOT, "passage %d (x %.2f..%.2f, y %.2f..%.2f)", p.id(), p.minX(), p.maxX(),
                p.minY(), p.maxY());
    }
}
