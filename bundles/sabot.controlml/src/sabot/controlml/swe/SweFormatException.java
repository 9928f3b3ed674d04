package sabot.controlml.swe;

/**
 * A SWE Common payload that ControlML cannot accept as written: not the subset {@link SweXml} reads (unknown or
 * misplaced elements, bad number syntax, extra attributes), or larger than the reader's budget.
 */
public final class SweFormatException extends Exception {

    private static final long serialVersionUID = 1L;

    /** What was wrong. */
    public enum Problem {
        /** the structure or a lexical form is wrong */
        MALFORMED,
        /** the payload exceeds the size budget */
        TOO_LARGE
    }

    private final Problem problem;

    public SweFormatException(Problem problem, String message) {
        super(message, null, false, false); // a value for the caller, not a stack trace
        this.problem = problem;
    }

    /** @return what was wrong */
    public Problem problem() {
        return problem;
    }
}
