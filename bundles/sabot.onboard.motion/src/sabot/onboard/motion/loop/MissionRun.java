package sabot.onboard.motion.loop;

import java.util.ArrayList;
import java.util.List;

import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MissionTarget;

/**
 * A mission of several targets as the loop runs it: the targets in order, each with its state, and the one the robot
 * is on its way to. The robot drives in legs: each leg goes through the pass targets ahead (one trajectory, no stop)
 * to the next target it stops on. Plain bookkeeping: the loop decides when a target is reached.
 */
final class MissionRun {

    private final List<MissionTarget> targets;
    private int current;
    /** The index of the first target of the leg being driven. */
    private int legStart;

    /** @param targets the mission's targets in order, at least one */
    MissionRun(List<MissionTarget> targets) {
        if (targets.isEmpty()) {
            throw new IllegalArgumentException("a mission needs at least one target");
        }
        this.targets = new ArrayList<>();
        for (MissionTarget t : targets) {
            this.targets.add(t.in(MissionTarget.State.PENDING));
        }
        this.targets.set(0, this.targets.get(0).in(MissionTarget.State.ACTIVE));
    }

    /** @return the targets with their states now (a copy) */
    List<MissionTarget> targets() {
        return List.copyOf(targets);
    }

    /** @return the index of the target the robot is on its way to; {@link #size()} once all are reached */
    int current() {
        return current;
    }

    int size() {
        return targets.size();
    }

    /** @return true while a target is left */
    boolean hasCurrent() {
        return current < targets.size();
    }

    /** @return the target the robot is on its way to; only while {@link #hasCurrent()} */
    MissionTarget target() {
        return targets.get(current);
    }

    /** @return the index of the target the current leg ends on: the next one that is not a pass, or the last */
    int legEnd() {
        for (int i = current; i < targets.size(); i++) {
            if (targets.get(i).action() != MissionTarget.Action.PASS) {
                return i;
            }
        }
        return targets.size() - 1;
    }

    /** @return the goal the current leg ends on */
    Goal legGoal() {
        return targets.get(legEnd()).goal();
    }

    /** @return the pass targets the current leg still goes through, in order */
    List<Goal> via() {
        List<Goal> via = new ArrayList<>();
        for (int i = current; i < legEnd(); i++) {
            via.add(targets.get(i).goal());
        }
        return via;
    }

    /** A new leg starts from the current target (its progress counts from here). */
    void legStarted() {
        legStart = current;
    }

    /** @return true while the robot is on its way to a pass target of the leg (not the leg's end) */
    boolean passing() {
        return hasCurrent() && current < legEnd();
    }

    /** The current target is reached: the next one (if any) becomes active. */
    void reached() {
        targets.set(current, target().in(MissionTarget.State.REACHED));
        current++;
        if (hasCurrent()) {
            targets.set(current, target().in(MissionTarget.State.ACTIVE));
        }
    }

    /** The mission ended on the way to the current target (failed or aborted). */
    void failed() {
        if (hasCurrent()) {
            targets.set(current, target().in(MissionTarget.State.FAILED));
        }
    }

    /**
     * @return the mission's progress, percent: the targets reached, plus the fraction {@code leg} of the current leg's
     *         trajectory (which covers its targets from {@link #legStarted()} to {@link #legEnd()})
     */
    double progress(double leg) {
        if (!hasCurrent()) {
            return 100;
        }
        double f = Math.max(0, Math.min(1, leg));
        double done = Math.max(current, legStart + f * (legEnd() + 1 - legStart));
        return Math.min(100, 100 * done / targets.size());
    }

    /** @return "target k of n", 1-based, for the operator */
    String label() {
        return "target " + Math.min(current + 1, targets.size()) + " of " + targets.size();
    }
}
