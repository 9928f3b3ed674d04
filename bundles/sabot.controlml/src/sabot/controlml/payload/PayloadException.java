package sabot.controlml.payload;

import java.util.Objects;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlError;

/** A payload that does not fit its resource's schema; carries the error to answer with. */
public final class PayloadException extends Exception {

    private static final long serialVersionUID = 1L;

    private final transient ControlMlError error;

    public PayloadException(ControlMlCondition condition, String message) {
        super(message, null, false, false);
        this.error = ControlMlError.of(condition, message);
    }

    /** @return the error to answer with; never null */
    public ControlMlError error() {
        return Objects.requireNonNull(error);
    }
}
