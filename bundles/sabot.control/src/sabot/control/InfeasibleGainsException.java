package sabot.control;

/** Controller gains that are not finite, not positive, or violate the law's convergence conditions. */
public final class InfeasibleGainsException extends IllegalArgumentException {

    private static final long serialVersionUID = 1L;

    public InfeasibleGainsException(String message) {
        super(message);
    }
}
