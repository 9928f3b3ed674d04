package sabot.onboard.motion.loop;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Instant;
import java.util.List;
import java.util.Optional;

import org.junit.jupiter.api.Test;

import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.map.OccupancyGrid;
import sabot.model.map.Passage;
import sabot.model.robot.PassageClaim;
import sabot.model.robot.PeerRobot;
import sabot.onboard.motion.loop.ControlLoop.Mode;

/**
 * The passage rule (docs/PASSAGES.md) with two real control loops in lockstep, each hearing the other as the peers
 * task would (pose, velocity and {@code cm.passage} claim, as late as the test says): two robots sent through one
 * door from opposite rooms at once. One goes first, the other yields short of the door; both arrive; their footprints
 * never overlap, and never are both in the door. A robot silent in the door holds it until the peer memory forgets it.
 */
class PassageLoopTest {

    private static final double TOUCH = 2 * LoopRig.ROBOT_RADIUS;
    /** The wall between the two rooms: x 5.0..5.1 m; its door y 4.5..5.5 m (1 m: one robot at a time). */
    private static final Passage DOOR = new Passage(1, 5.0, 4.5, 5.1, 5.5);
    private static final String A = LoopPair.A, B = LoopPair.B;

    /** @return the 10 m × 10 m map with the wall and its door */
    static OccupancyGrid doorMap() {
        OccupancyGrid map = LoopRig.emptyMap();
        for (int row = 0; row < 200; row++) {
            double y = (row + 0.5) * 0.05;
            if (y > DOOR.minY() && y < DOOR.maxY()) {
                continue;
            }
            map.set(100, row, OccupancyGrid.OCCUPIED);
            map.set(101, row, OccupancyGrid.OCCUPIED);
        }
        return map;
    }

    private static void crossAtOnce(int lagPeriods) {
        LoopPair p = new LoopPair(doorMap(), new Pose2D(2, 6, 0), new Pose2D(8, 4, Math.PI), lagPeriods, List.of(
                DOOR));
        p.tick();
        p.send(p.a, 8, 6, 0);
        p.send(p.b, 2, 4, Math.PI);
        p.runMissions(90);
        assertEquals(MissionState.DONE, p.state(p.a), p.a.loop.snapshot().mission().detail());
        assertEquals(MissionState.DONE, p.state(p.b), p.b.loop.snapshot().mission().detail());
        assertTrue(p.aYielded ^ p.bYielded, "exactly one robot yields: a " + p.aYielded + ", b " + p.bYielded);
        assertFalse(p.bothPassing, "both held the door at once");
        assertFalse(p.bothIn(DOOR), "both footprints were in the door at once");
        assertTrue(p.closest >= TOUCH, "footprints overlapped: centres " + p.closest + " m apart");
        assertEquals(Optional.empty(), p.a.loop.snapshot().passage(), "a let the door go");
        assertEquals(Optional.empty(), p.b.loop.snapshot().passage(), "b let the door go");
    }

    /** Both sent at once, each hearing the other at once: one goes, the other yields; no contact, no deadlock. */
    @Test
    void twoRobotsAtOneDoorTakeTurns() {
        crossAtOnce(0);
    }

    /**
     * Each hears the other 0.4 s late (two periods of the 5 Hz telemetry): the requests made at one instant are still
     * ordered the same way on both, because a request stands {@link PassageRule#SETTLE} seconds before it is taken.
     */
    @Test
    void twoRobotsAtOneDoorTakeTurnsWhenTheyHearEachOtherLate() {
        crossAtOnce(20);
    }

    /**
     * A robot that took the door falls silent on its way to it: its claim holds the door for as long as the peer
     * memory remembers it, then the other goes on, and never earlier.
     */
    @Test
    void aSilentRobotsClaimHoldsTheDoorUntilThePeerMemoryForgetsIt() {
        LoopRig rig = new LoopRig(doorMap(), new Pose2D(2, 5, 0));
        Instant heard = rig.clock.now();
        PeerRobot silent = new PeerRobot(B, new Pose2D(7, 8, Math.PI), new Twist2D(0, 0), heard, true,
                new PassageClaim(1, PassageClaim.State.PASSING, heard));
        rig.loop.peersFrom(() -> List.of(silent), () -> A, new PeerSettings(5, LoopDefaults.PASSAGE_APPROACH, 60));
        rig.loop.passages(List.of(DOOR));
        rig.tick();
        Goal g = new Goal(new Pose2D(8, 5, 0), 0.1, 0.2);
        ControlLoop.Plan plan = rig.loop.planPath(rig.loop.snapshot().pose().pose(), g, List.of());
        assertNull(plan.refusal());
        rig.loop.startMission(g, plan);
        ControlLoop.Snapshot s = null;
        double yieldedAt = Double.NaN;
        for (int i = 0; i < 60 * 50 && (s == null || s.mission().state() == MissionState.RUNNING); i++) {
            s = rig.tick();
            rig.answerPlanRequests();
            double t = (i + 1) * 0.02;
            if (s.mode() == Mode.YIELD && Double.isNaN(yieldedAt)) {
                yieldedAt = t;
                assertTrue(s.pose().pose().x() < DOOR.minX() - LoopRig.ROBOT_RADIUS - 0.5, "stopped short: "
                        + s.pose());
                assertEquals(PassageClaim.State.WAITING, s.passage().orElseThrow().state());
                assertTrue(s.mission().detail().endsWith("; yielding at passage 1: " + B + " passes"), "the "
                        + "operator reads why it stands: " + s.mission().detail());
            }
            if (t < 5 && !Double.isNaN(yieldedAt)) {
                assertEquals(Mode.YIELD, s.mode(), "went on at " + t + " s, while the silent claim counted");
            }
        }
        assertFalse(Double.isNaN(yieldedAt), "never yielded");
        assertEquals(MissionState.DONE, s.mission().state(), s.mission().detail());
        assertEquals(Optional.empty(), s.passage());
    }
}
