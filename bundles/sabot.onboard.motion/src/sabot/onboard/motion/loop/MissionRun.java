package sabot.onboard.motion.loop;

import java.util.ArrayList;
import java.util.List;

import sabot.controlml.payload.MissionTarget;

/**
 * A mission of several targets as the loop runs it: the targets in order, each with its state, and the one the robot
 * is on its way to. Plain bookkeeping: the loop decides when a target is reached.
 */
final class MissionRun {

    private final List<MissionTarget> targets;
    private int current;

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

    /** @return true when the robot drives through the current target into a next one (a pass that is not the last) */
    boolean passing() {
        return hasCurrent() && target().action() == MissionTarget.Action.PASS && current + 1 < targets.size();
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

    /** @return the mission's progress, percent: the targets reached plus the fraction {@code leg} of the current one */
    double progress(double leg) {
        return Math.min(100, 100 * (current + Math.max(0, Math.min(1, leg))) / targets.size());
    }

    /** @return "target k of n", 1-based, for the operator */
    String label() {
        return "target " + Math.min(current + 1, targets.size()) + " of " + targets.size();
    }
}
