package sabot.control.trajectory;

/** Waypoints that cannot define a path: too few distinct points, or a NaN/infinite coordinate. */
public final class InvalidPathException extends IllegalArgumentException {

    private static final long serialVersionUID = 1L;

    public InvalidPathException(String message) {
        super(message);
    }
}
