package sabot.controlml;

/** The {@code type} attribute of {@code <control-ml/>}. */
public enum ControlMlType {
    /** read a resource */
    GET,
    /** write a resource */
    SET,
    /** the answer to a get or set; also the type of telemetry items */
    RESULT,
    /** the answer to a get or set that failed */
    ERROR;

    /** Written on every request and answer: computed once, not per serialisation. */
    private final String attribute = name().toLowerCase(java.util.Locale.ROOT);

    /** @return the attribute value, e.g. {@code get} */
    public String attribute() {
        return attribute;
    }

    /** @return the type for an attribute value, or null when it is not one of get|set|result|error */
    public static ControlMlType fromAttribute(String value) {
        if (value == null) {
            return null;
        }
        return switch (value) {
            case "get" -> GET;
            case "set" -> SET;
            case "result" -> RESULT;
            case "error" -> ERROR;
            default -> null;
        };
    }

    /** @return true for get and set */
    public boolean isRequest() {
        return this == GET || this == SET;
    }
}
