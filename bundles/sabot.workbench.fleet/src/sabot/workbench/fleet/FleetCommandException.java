package sabot.workbench.fleet;

import java.util.Objects;
import java.util.concurrent.CompletionException;
import java.util.concurrent.ExecutionException;

import sabot.controlml.ControlMlCondition;

/**
 * Why a robot (or the way to it) refused or failed a command: the ControlML error condition (docs/CONTROLML.md
 * section 8) and its text, meant for the operator. The futures of {@link FleetState} complete exceptionally with it.
 */
public final class FleetCommandException extends RuntimeException {

    private static final long serialVersionUID = 1L;

    private final transient ControlMlCondition condition;
    private final String text;

    /**
     * @param condition the ControlML condition, e.g. {@link ControlMlCondition#INVALID_VALUE}; never null
     * @param text      the robot's (or the client's) explanation; never null
     */
    public FleetCommandException(ControlMlCondition condition, String text) {
        super(condition.element() + ": " + text);
        this.condition = Objects.requireNonNull(condition, "condition");
        this.text = Objects.requireNonNull(text, "text");
    }

    /** @return the ControlML condition */
    public ControlMlCondition condition() {
        return condition;
    }

    /** @return the explanation, as the robot wrote it */
    public String text() {
        return text;
    }

    /**
     * @return the command failure inside what a future threw ({@link CompletionException},
     *         {@link ExecutionException}), or null when the failure is of another kind
     */
    public static FleetCommandException in(Throwable thrown) {
        Throwable t = thrown;
        while ((t instanceof CompletionException || t instanceof ExecutionException) && t.getCause() != null) {
            t = t.getCause();
        }
        return t instanceof FleetCommandException f ? f : null;
    }
}
