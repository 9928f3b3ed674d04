package sabot.controlml;

import org.jivesoftware.smack.packet.StanzaError;

/**
 * ControlML's application-specific error conditions (RFC 6120 section 8.3.2: an element in
 * {@value ControlMl#ERRORS_NAMESPACE} next to the defined condition), each with the RFC 6120 condition it is
 * reported under.
 */
public enum ControlMlCondition {
    /** attributes of {@code control-ml} missing, unknown, or with invalid values */
    BAD_ATTRIBUTES("bad-attributes", StanzaError.Condition.bad_request),
    /** {@code id} is not {@code YYYYMMDD:UINT32} */
    BAD_ID("bad-id", StanzaError.Condition.bad_request),
    /** the control-ml type does not fit the carrier (e.g. {@code type='set'} in an {@code iq type='get'}) */
    TYPE_MISMATCH("type-mismatch", StanzaError.Condition.bad_request),
    /** the content is not the SWE Common subset ControlML reads, or not the resource's payload structure */
    MALFORMED_PAYLOAD("malformed-payload", StanzaError.Condition.bad_request),
    /** a set without payload, or a get/set whose resource takes no such payload */
    PAYLOAD_MISMATCH("payload-mismatch", StanzaError.Condition.bad_request),
    /** {@code res} is not in the resource catalogue */
    UNKNOWN_RESOURCE("unknown-resource", StanzaError.Condition.item_not_found),
    /** the resource exists but this device does not serve this operation on it */
    UNSUPPORTED_OPERATION("unsupported-operation", StanzaError.Condition.service_unavailable),
    /** the payload is larger than {@link ControlMl#MAX_PAYLOAD_CHARS} */
    PAYLOAD_TOO_LARGE("payload-too-large", StanzaError.Condition.not_acceptable),
    /** a value is NaN, infinite or out of its range */
    INVALID_VALUE("invalid-value", StanzaError.Condition.not_acceptable),
    /** a quantity is in a unit of the wrong dimension, or in an unknown unit */
    WRONG_UNIT("wrong-unit", StanzaError.Condition.not_acceptable),
    /** the command waited longer than the robot's stale-command limit */
    STALE_COMMAND("stale-command", StanzaError.Condition.not_acceptable),
    /** the requester has no role on this device: it may not use ControlML there at all */
    ACCESS_DENIED("access-denied", StanzaError.Condition.forbidden),
    /** the requester's role does not include this set (an observer's set; an operator's set of PID gains) */
    SET_NOT_PERMITTED("set-not-permitted", StanzaError.Condition.forbidden),
    /** the device is in maintenance mode and takes commands from its maintainers only */
    MAINTENANCE_LOCK("maintenance-lock", StanzaError.Condition.not_authorized),
    /** the command is valid but not in the device's current state (e.g. a joystick twist during a mission) */
    INVALID_STATE("invalid-state", StanzaError.Condition.unexpected_request),
    /** the device cannot take the command now (queue full, rate limit); retry later */
    BUSY("busy", StanzaError.Condition.resource_constraint),
    /** the device's hardware or a service behind it failed */
    DEVICE_FAULT("device-fault", StanzaError.Condition.service_unavailable),
    /** local: no answer arrived within the request timeout */
    TIMEOUT("timeout", StanzaError.Condition.remote_server_timeout),
    /** local: the request could not be sent (not connected) */
    NOT_CONNECTED("not-connected", StanzaError.Condition.recipient_unavailable),
    /** an error answer without a ControlML condition (e.g. the server's own service-unavailable) */
    UNSPECIFIED("unspecified", StanzaError.Condition.undefined_condition);

    private final String element;
    private final StanzaError.Condition stanzaCondition;

    ControlMlCondition(String element, StanzaError.Condition stanzaCondition) {
        this.element = element;
        this.stanzaCondition = stanzaCondition;
    }

    /** @return the element name in {@value ControlMl#ERRORS_NAMESPACE} */
    public String element() {
        return element;
    }

    /** @return the RFC 6120 condition this condition is reported under */
    public StanzaError.Condition stanzaCondition() {
        return stanzaCondition;
    }

    /** @return the condition with this element name, or null */
    public static ControlMlCondition fromElement(String element) {
        for (ControlMlCondition c : values()) {
            if (c.element.equals(element)) {
                return c;
            }
        }
        return null;
    }
}
