package sabot.onboard.motion.loop;

import java.time.Instant;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Deque;
import java.util.List;
import java.util.concurrent.atomic.AtomicReference;

import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.model.geometry.Pose2D;
import sabot.model.map.OccupancyGrid;
import sabot.model.map.Passage;
import sabot.model.robot.PassageClaim;
import sabot.model.robot.PeerRobot;
import sabot.onboard.motion.loop.ControlLoop.Mode;

/**
 * Two real control loops ({@link LoopRig}) in lockstep on one map, each hearing the other as the peers task would
 * (pose, velocity and passage claim), as late as the test says; what happened between them is recorded period by
 * period.
 */
final class LoopPair {

    static final String A = "sabot-01@sabot.local", B = "sabot-02@sabot.local";

    final LoopRig a;
    final LoopRig b;
    private final AtomicReference<List<PeerRobot>> heardByA = new AtomicReference<>(List.of());
    private final AtomicReference<List<PeerRobot>> heardByB = new AtomicReference<>(List.of());
    private final Deque<PeerRobot> fromA = new ArrayDeque<>(), fromB = new ArrayDeque<>();
    private final int lag;
    /** Every period's two poses, in order. */
    final List<Pose2D[]> poses = new ArrayList<>();
    double closest = Double.POSITIVE_INFINITY;
    boolean aYielded, bYielded, bothPassing;

    /**
     * @param lagPeriods periods after which each hears the other's state
     * @param passages   the map's narrow passages
     */
    LoopPair(OccupancyGrid map, Pose2D startA, Pose2D startB, int lagPeriods, List<Passage> passages) {
        a = new LoopRig(map, startA);
        b = new LoopRig(map, startB);
        lag = lagPeriods;
        PeerSettings s = new PeerSettings(5, LoopDefaults.PASSAGE_APPROACH, 60);
        a.loop.peersFrom(heardByA::get, () -> A, s);
        b.loop.peersFrom(heardByB::get, () -> B, s);
        a.loop.passages(passages);
        b.loop.passages(passages);
    }

    /** One period of both, then each hears the other as it was {@code lag} periods ago. */
    void tick() {
        ControlLoop.Snapshot sa = a.tick();
        ControlLoop.Snapshot sb = b.tick();
        a.answerPlanRequests();
        b.answerPlanRequests();
        fromA.addLast(peer(A, sa, a.clock.now()));
        fromB.addLast(peer(B, sb, b.clock.now()));
        if (fromA.size() > lag) {
            heardByB.set(List.of(fromA.removeFirst()));
        }
        if (fromB.size() > lag) {
            heardByA.set(List.of(fromB.removeFirst()));
        }
        Pose2D pa = sa.pose().pose();
        Pose2D pb = sb.pose().pose();
        poses.add(new Pose2D[] { pa, pb });
        closest = Math.min(closest, Math.hypot(pa.x() - pb.x(), pa.y() - pb.y()));
        aYielded |= sa.mode() == Mode.YIELD;
        bYielded |= sb.mode() == Mode.YIELD;
        bothPassing |= passing(sa) && passing(sb);
    }

    /** @return whether both footprints were ever in {@code p} in one period */
    boolean bothIn(Passage p) {
        return poses.stream().anyMatch(two -> p.touches(two[0].x(), two[0].y(), LoopRig.ROBOT_RADIUS) && p.touches(
                two[1].x(), two[1].y(), LoopRig.ROBOT_RADIUS));
    }

    private static boolean passing(ControlLoop.Snapshot s) {
        return s.passage().map(c -> c.state() == PassageClaim.State.PASSING).orElse(false);
    }

    private static PeerRobot peer(String jid, ControlLoop.Snapshot s, Instant heard) {
        return new PeerRobot(jid, s.pose().pose(), s.velocity().twist(), heard, true, s.passage().orElse(null));
    }

    /** Sends a robot to (x, y, theta), planned as the motion task plans a goal. */
    void send(LoopRig rig, double x, double y, double theta) {
        Goal g = new Goal(new Pose2D(x, y, theta), 0.1, 0.2);
        rig.loop.startMission(g, rig.loop.planPath(rig.loop.snapshot().pose().pose(), g, List.of()));
    }

    MissionState state(LoopRig rig) {
        return rig.loop.snapshot().mission().state();
    }

    /** Ticks until neither mission runs, for at most {@code seconds}. */
    void runMissions(double seconds) {
        for (int i = 0; i < seconds * 50 && (state(a) == MissionState.RUNNING || state(b) == MissionState.RUNNING);
                i++) {
            tick();
        }
    }
}
