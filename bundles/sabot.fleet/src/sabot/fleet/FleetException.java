package sabot.fleet;

/** A fleet operation that could not be done (the cause says why). */
public final class FleetException extends Exception {

    private static final long serialVersionUID = 1L;

    public FleetException(String message, Throwable cause) {
        super(message, cause);
    }
}
