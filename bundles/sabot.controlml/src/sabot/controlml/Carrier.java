package sabot.controlml;

/** The stanza a ControlML request arrived in. */
public enum Carrier {
    /** an {@code <iq/>}: online request/response */
    IQ,
    /** a {@code <message/>} to the bare JID: queued by the server while the robot was offline */
    MESSAGE
}
