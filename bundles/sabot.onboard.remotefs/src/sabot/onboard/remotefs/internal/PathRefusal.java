package sabot.onboard.remotefs.internal;

import java.util.Objects;

/** Why {@link ConfinedRoot} will not hand out a path: a value the service turns into a ControlML error. */
public final class PathRefusal extends Exception {

    private static final long serialVersionUID = 1L;

    /** The kinds of refusal, each reported under its own ControlML condition. */
    public enum Reason {
        /**
         * The text is not a remote-FS path: absolute, a {@code .} or {@code ..} or empty segment, a backslash, a NUL
         * or other control character, a segment too long, or a name reserved for transfers in progress.
         */
        MALFORMED,
        /** The path resolves (through a symbolic link) outside the root, or through a link that points nowhere. */
        OUTSIDE_ROOT,
        /** Nothing exists under the path. */
        NOT_FOUND,
        /** A segment before the last names a file, not a directory. */
        NOT_A_DIRECTORY
    }

    private final Reason reason;

    public PathRefusal(Reason reason, String message) {
        super(message);
        this.reason = Objects.requireNonNull(reason);
    }

    /** @return why the path was refused; never null */
    public Reason reason() {
        return reason;
    }
}
