package sabot.controlml;

/** What a requester may do on a device. */
public enum AccessLevel {
    /** nothing: every request is answered {@code forbidden} */
    NONE,
    /** get only: a set is answered {@code forbidden} */
    GET,
    /** get and set */
    SET;

    /** @return true when this level allows the request type */
    public boolean allows(ControlMlType type) {
        return switch (type) {
            case GET -> this != NONE;
            case SET -> this == SET;
            default -> false;
        };
    }
}
