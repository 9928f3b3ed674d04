package sabot.controlml.payload;

import java.util.Locale;
import java.util.Objects;

/**
 * One target of a mission ({@code cm.mission}'s {@code target0…}): where to go, what to do there, and how far the
 * robot has got with it.
 *
 * @param goal   the target pose and its tolerances; never null
 * @param action what the robot does on reaching it; never null
 * @param dwell  seconds the robot stands at the target (the wire's {@code wait}), 0..{@value #MAX_WAIT_S}; greater than 0 exactly for
 *               {@link Action#WAIT}
 * @param state  how far the robot has got with it; never null (a new mission's targets are {@link State#PENDING})
 */
public record MissionTarget(Goal goal, Action action, double dwell, State state) {

    /** Longest wait at a target, seconds. */
    public static final double MAX_WAIT_S = 3600;

    public MissionTarget {
        Objects.requireNonNull(goal, "goal");
        Objects.requireNonNull(action, "action");
        Objects.requireNonNull(state, "state");
        if (!(dwell >= 0 && dwell <= MAX_WAIT_S)) {
            throw new IllegalArgumentException("wait must be 0.." + MAX_WAIT_S + " s, was " + dwell);
        }
        if ((action == Action.WAIT) != (dwell > 0)) {
            throw new IllegalArgumentException(action == Action.WAIT ? "a wait target needs a wait above 0 s"
                    : "only a wait target waits (action " + action.code() + ", wait " + dwell + " s)");
        }
    }

    /** @return a target not yet started */
    public static MissionTarget pending(Goal goal, Action action, double dwell) {
        return new MissionTarget(goal, action, dwell, State.PENDING);
    }

    /** @return this target in another state */
    public MissionTarget in(State s) {
        return new MissionTarget(goal, action, dwell, s);
    }

    /** What the robot does on reaching a target. */
    public enum Action {
        /** drives through it without stopping: the next leg starts once it is within the position tolerance */
        PASS,
        /** stops on it (position and heading within the tolerances), then goes on */
        STOP,
        /** stops on it and stands {@code wait} seconds, then goes on */
        WAIT,
        /** stops on it: the robot's dock (a charger where the map has one) */
        DOCK;

        /** @return the code, e.g. {@code pass} */
        public String code() {
            return name().toLowerCase(Locale.ROOT);
        }
    }

    /** How far the robot has got with a target. */
    public enum State {
        /** not yet started */
        PENDING,
        /** the robot is on its way to it (or waits on it) */
        ACTIVE,
        /** reached (and its wait done) */
        REACHED,
        /** the mission failed or was aborted on the way to it */
        FAILED;

        /** @return the code, e.g. {@code reached} */
        public String code() {
            return name().toLowerCase(Locale.ROOT);
        }
    }
}
