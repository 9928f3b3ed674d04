package sabot.controlml;

import java.util.Locale;

/**
 * What a requester may do on a device (docs/CONTROLML.md section 9). Each role includes the ones before it: an
 * operator may do what an observer may, a maintainer what an operator may.
 */
public enum Role {
    /** nothing: every request is answered {@code access-denied} */
    NONE,
    /** every get, and the device's presence and telemetry */
    OBSERVER,
    /** what moves the robot or stops it: goals, trajectories, joystick twists, re-localisation, mission commands */
    OPERATOR,
    /**
     * what changes the robot itself: PID gains and the step test, limits, the map, the remote file system's writes
     * and deletes, maintenance mode
     */
    MAINTAINER;

    /** @return true when this role may do what {@code needed} may */
    public boolean includes(Role needed) {
        return compareTo(needed) >= 0;
    }

    /** @return the role's name as the spec and the configuration write it, e.g. {@code operator} */
    public String label() {
        return name().toLowerCase(Locale.ROOT);
    }

    /** @return the role with its article, as the refusals write it: "an observer", "a maintainer", "no role" */
    public String withArticle() {
        return switch (this) {
            case NONE -> "no role";
            case OBSERVER, OPERATOR -> "an " + label();
            case MAINTAINER -> "a " + label();
        };
    }

    /**
     * @param label a role's {@link #label()}
     * @return the role
     * @throws IllegalArgumentException for another word, naming the roles there are
     */
    public static Role ofLabel(String label) {
        for (Role r : values()) {
            if (r != NONE && r.label().equals(label)) {
                return r;
            }
        }
        throw new IllegalArgumentException("'" + label + "' is not a role: observer, operator or maintainer");
    }
}
