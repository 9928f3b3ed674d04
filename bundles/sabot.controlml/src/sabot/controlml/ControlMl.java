package sabot.controlml;

/**
 * Names and limits of the ControlML wire format (see {@code docs/CONTROLML.md} and {@code docs/controlml.xsd}).
 * <p>
 * A {@code <control-ml/>} element in namespace {@value #NAMESPACE} travels inside an {@code <iq/>} (requests and
 * their answers), a {@code <message/>} (commands queued for an offline robot, and their answers) or a PEP item
 * (telemetry). Its attributes are exactly {@code type} (get|set|result|error), {@code id} ({@code YYYYMMDD:UINT32})
 * and {@code res} (a resource name such as {@code cm.position}); its content is at most one SWE Common 2.0
 * component (the payload) or, for {@code type='error'}, one {@code <failure/>}.
 */
public final class ControlMl {

    /** Namespace of {@code control-ml}, {@code failure} and {@code presence-level}. */
    public static final String NAMESPACE = "urn:sabot:controlml:1";
    /** Namespace of the application-specific error conditions inside a stanza {@code <error/>}. */
    public static final String ERRORS_NAMESPACE = "urn:sabot:controlml:1:errors";
    /** The element name. */
    public static final String ELEMENT = "control-ml";
    /**
     * Largest payload accepted: 65,536 in ControlML's payload size, i.e. code points of the payload element written
     * in a canonical way (no namespace declarations, prefixes or comments; every element as a start and an end tag;
     * text after entity expansion): see {@code docs/CONTROLML.md} section 1 and {@link sabot.controlml.swe.SweXml.Budget}.
     */
    public static final int MAX_PAYLOAD_CHARS = 64 * 1024;
    /** Prefix of the PEP node of a resource's telemetry: node = prefix + resource name. */
    public static final String TELEMETRY_NODE_PREFIX = NAMESPACE + ":telemetry:";
    /**
     * Prefix of the reference to a resource's record structure, by which a payload in the text form names it:
     * {@code xlink:href} = prefix + resource name (see {@link Resource#recordTemplate()}).
     */
    public static final String RECORD_STRUCTURE_PREFIX = NAMESPACE + ":record:";
    /** Service discovery feature a ControlML endpoint announces. */
    /**
     * A requester's default wait for an answer, s ({@link ControlMlManager#setRequestTimeout}).
     */
    public static final int DEFAULT_REQUEST_TIMEOUT_S = 10;
    /**
     * A device's default stale-command limit, s ({@link StaleCommandPolicy#DEFAULT}): below
     * {@link #DEFAULT_REQUEST_TIMEOUT_S}, so that a command its operator saw time out is never applied (section 5).
     */
    public static final int DEFAULT_STALE_COMMAND_S = 5;
    public static final String FEATURE = NAMESPACE;

    private ControlMl() {
    }

    /** @return the PEP node carrying a resource's telemetry, e.g. {@code urn:sabot:controlml:1:telemetry:cm.position} */
    public static String telemetryNode(String resourceName) {
        return TELEMETRY_NODE_PREFIX + resourceName;
    }
}
