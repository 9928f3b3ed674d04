package sabot.controlml.payload;

import java.util.Locale;

/** The state of the robot's mission (the {@code state} code of {@code cm.mission}). */
public enum MissionState {
    /** no mission */
    IDLE,
    /** driving to a goal */
    RUNNING,
    /** halted, resumable */
    PAUSED,
    /** reached the goal */
    DONE,
    /** gave up (unreachable goal, fault) */
    FAILED,
    /** an operator aborted it */
    ABORTED,
    /**
     * waits in the robot's queue: only in a set that carries targets (append this mission to the queue); never the
     * state of the robot's mission
     */
    QUEUED;

    /** @return the code, e.g. {@code running} */
    public String code() {
        return name().toLowerCase(Locale.ROOT);
    }

    /** @return the state of a code, or null */
    public static MissionState fromCode(String code) {
        for (MissionState s : values()) {
            if (s.code().equals(code)) {
                return s;
            }
        }
        return null;
    }

    /** @return true while the robot works on a mission (running or paused) */
    public boolean isActive() {
        return this == RUNNING || this == PAUSED;
    }
}
