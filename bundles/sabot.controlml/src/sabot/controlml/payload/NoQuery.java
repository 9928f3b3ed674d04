package sabot.controlml.payload;

/** The query type of resources whose {@code get} carries no payload. */
public enum NoQuery {
    /** the only value */
    NONE
}
