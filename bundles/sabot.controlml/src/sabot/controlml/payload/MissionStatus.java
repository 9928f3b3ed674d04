package sabot.controlml.payload;

import java.util.Objects;

/**
 * {@code cm.mission}: the mission state (get), or a requested transition (set: pause, resume, abort, maintenance).
 *
 * @param state       the state; never null
 * @param maintenance whether the robot is in maintenance mode
 * @param progress    percent of the path done, 0..100
 * @param detail      a short explanation for operators; never null
 */
public record MissionStatus(MissionState state, boolean maintenance, double progress, String detail) {
    public MissionStatus {
        Objects.requireNonNull(state, "state");
        Objects.requireNonNull(detail, "detail");
    }
}
