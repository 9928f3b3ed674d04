package sabot.system;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.TreeSet;
import java.util.concurrent.TimeUnit;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import sabot.controlml.Resources;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.controlml.payload.MissionTarget.Action;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.robot.SimProcess;

/**
 * Issue 34's first proof: a mission of four targets, with a pass and a wait, sent over XMPP to the onboard product on
 * the simulator. Judged on the simulator's truth: the targets are reached in order, the robot drives through the
 * pass target and stands on the wait target for its time; the robot reports each target's progress; an abort midway
 * through a second mission stops the robot.
 */
class MissionTest extends RigTest {

    /** Position tolerance of every target, m, judged on the truth (as {@link NavigationTest}). */
    static final double TOLERANCE = 0.15;
    /** How long the robot stands on the wait target, s. */
    static final double WAIT = 1.0;
    /** The lower corridor, west to east from x = 1.5 m: a pass, a wait, a stop off the corridor's axis, a stop. */
    static final List<MissionTarget> FOUR = List.of(target(2.5, 1.0, 0, Action.PASS, 0), target(3.5, 1.0, 0,
            Action.WAIT, WAIT), target(4.5, 1.5, 0, Action.STOP, 0), target(5.5, 1.0, 0, Action.STOP, 0));

    static MissionTarget target(double x, double y, double theta, Action action, double wait) {
        return MissionTarget.pending(new Goal(new Pose2D(x, y, theta), TOLERANCE, 0.3), action, wait);
    }

    static MissionStatus start(List<MissionTarget> targets) {
        return new MissionStatus(MissionState.RUNNING, false, 0, "", targets, 0, 0);
    }

    @Test
    void fourTargetsAreReachedInOrderAndAnAbortStopsTheNextMission(@TempDir Path dir) throws Exception {
        try (RobotRig rig = RobotRig.start(xmpp, dir, CORRIDOR_WEST, new String[0], "")) {
            assertTrue(rig.operator.set(rig.robot, Resources.MISSION, start(FOUR)).isSuccess(), rig.onboard
                    .output());
            // the truth every 20 ms and the robot's report every 10th sample, until it says the mission is over
            List<SimProcess.Truth> truths = new ArrayList<>();
            TreeSet<Integer> currents = new TreeSet<>();
            List<Integer> reported = new ArrayList<>();
            MissionStatus m = rig.get(Resources.MISSION);
            double deadline = rig.sim.truth().t() + 120;
            for (int i = 0; m.state() == MissionState.RUNNING; i++) {
                SimProcess.Truth t = rig.sim.truth();
                truths.add(t);
                assertTrue(t.t() < deadline, "mission not done within 120 s: " + m + "\n" + rig.onboard.output());
                if (i % 10 == 0) {
                    m = rig.get(Resources.MISSION);
                    currents.add(m.current());
                    if (reported.isEmpty() || reported.get(reported.size() - 1) != m.current()) {
                        reported.add(m.current());
                    }
                }
                TimeUnit.MILLISECONDS.sleep(20);
            }
            assertEquals(MissionState.DONE, m.state(), m + "\n" + rig.onboard.output());
            assertEquals("all 4 targets reached", m.detail());
            assertEquals(4, m.current());
            assertTrue(m.targets().stream().allMatch(t -> t.state() == MissionTarget.State.REACHED), m.toString());
            assertEquals(new ArrayList<>(new TreeSet<>(reported)), reported, "progress only forward: " + reported);
            assertTrue(currents.size() >= 4, "the robot reported each target on the way: " + currents);

            // on the truth: each target reached (within the tolerance), in order
            double[] firstAt = new double[FOUR.size()];
            int next = 0;
            for (SimProcess.Truth t : truths) {
                if (next < FOUR.size() && within(t, FOUR.get(next))) {
                    firstAt[next++] = t.t();
                }
            }
            assertEquals(FOUR.size(), next, "targets reached in order on the truth: " + next + "; last "
                    + truths.get(truths.size() - 1));
            // the pass: the robot never stood near it; the wait: it stood there about WAIT seconds
            double slowestAtPass = truths.stream().filter(t -> within(t, FOUR.get(0))).mapToDouble(t -> Math.abs(t
                    .v())).min().orElseThrow();
            // from the truth file (every step of the simulator), not from the polled truths: a poll held up by the
            // mission's get under load would cut the stand short
            double stoodAtWait = longestStand(truthFile(rig.sim), FOUR.get(1));
            SimProcess.Truth end = rig.sim.truth();
            System.out.printf("[mission] targets first reached at t = %.1f, %.1f, %.1f, %.1f s; slowest at the pass "
                    + "%.2f m/s; stood %.2f s on the wait target; end %s%n", firstAt[0], firstAt[1], firstAt[2],
                    firstAt[3], slowestAtPass, stoodAtWait, end);
            assertTrue(slowestAtPass > 0.05, "drove through the pass target: slowest " + slowestAtPass + " m/s");
            // the wait starts once the robot is at rest by its own measure (under 0.05 m/s, then braked): the truth's
            // standstill (5 mm/s) comes up to 0.1 s (0.05 m/s at 0.5 m/s²) plus a period later
            assertTrue(stoodAtWait >= WAIT - 0.15 && stoodAtWait <= WAIT + 1.0, "stood " + stoodAtWait
                    + " s on the wait target, " + WAIT + " s asked");
            assertTrue(within(end, FOUR.get(3)), "at the last target: " + end);
            assertEquals(0, end.contacts(), "contacts: " + end);

            // a second mission, back west: aborted on the way to its second target, the robot stops and stays
            List<MissionTarget> back = List.of(target(4.5, 1.0, Math.PI, Action.PASS, 0), target(2.0, 1.0, Math.PI,
                    Action.STOP, 0));
            assertTrue(rig.operator.set(rig.robot, Resources.MISSION, start(back)).isSuccess());
            awaitTruth(rig.sim, t -> t.x() < 4.0 && Math.abs(t.v()) > 0.15, 60, "driving past the first target");
            assertEquals(1, rig.get(Resources.MISSION).current(), "on its way to the second target");
            assertTrue(rig.operator.set(rig.robot, Resources.MISSION, new MissionStatus(MissionState.ABORTED, false,
                    0, "the test")).isSuccess());
            SimProcess.Truth stopped = awaitStandstill(rig.sim, 3);
            MissionStatus aborted = rig.get(Resources.MISSION);
            assertEquals(MissionState.ABORTED, aborted.state());
            assertEquals(List.of(MissionTarget.State.REACHED, MissionTarget.State.FAILED), aborted.targets().stream()
                    .map(MissionTarget::state).toList());
            SimProcess.Truth later = awaitSimTime(rig.sim, 2);
            assertTrue(Math.hypot(later.x() - stopped.x(), later.y() - stopped.y()) < 0.02, "stays: " + stopped
                    + " then " + later);
            assertTrue(later.x() > 2.5, "stopped short of the aborted target: " + later);
        }
    }

    static boolean within(SimProcess.Truth t, MissionTarget target) {
        return t.distanceTo(target.goal().pose().x(), target.goal().pose().y()) <= TOLERANCE;
    }

    /** @return robot 1's rows of the simulator's truth file so far, as truths */
    static List<SimProcess.Truth> truthFile(SimProcess sim) throws java.io.IOException {
        List<SimProcess.Truth> out = new ArrayList<>();
        for (String[] r : sim.truthRows()) {
            if (r[1].trim().equals("1")) {
                out.add(new SimProcess.Truth(Double.parseDouble(r[0]), Double.parseDouble(r[2]), Double.parseDouble(
                        r[3]), Double.parseDouble(r[4]), Double.parseDouble(r[5]), Double.parseDouble(r[6]), Long
                                .parseLong(r[11].trim())));
            }
        }
        return out;
    }

    /** @return the longest time the truth stood still within the target's tolerance, s */
    static double longestStand(List<SimProcess.Truth> truths, MissionTarget target) {
        double longest = 0;
        double since = Double.NaN;
        for (SimProcess.Truth t : truths) {
            boolean standing = within(t, target) && Math.abs(t.v()) < 0.005 && Math.abs(t.omega()) < 0.01;
            if (standing && Double.isNaN(since)) {
                since = t.t();
            } else if (!standing) {
                since = Double.NaN;
            }
            if (!Double.isNaN(since)) {
                longest = Math.max(longest, t.t() - since);
            }
        }
        return longest;
    }
}
