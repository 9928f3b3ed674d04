package sabot.model.robot;

import java.util.List;

/** A robot description that is missing a value, has a malformed one, or is physically inconsistent. */
public final class InvalidRobotDescriptionException extends IllegalArgumentException {

    private static final long serialVersionUID = 1L;

    private final List<String> problems;

    public InvalidRobotDescriptionException(List<String> problems) {
        super("invalid robot description: " + String.join("; ", problems));
        this.problems = List.copyOf(problems);
    }

    /** @return every problem found, one human-readable sentence each (never empty) */
    public List<String> problems() {
        return problems;
    }
}
