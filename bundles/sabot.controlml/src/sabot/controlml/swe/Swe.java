package sabot.controlml.swe;

/** Constants of the SWE Common Data Model 2.0 encoding used by ControlML. */
public final class Swe {

    /** The SWE Common 2.0 namespace. */
    public static final String NAMESPACE = "http://www.opengis.net/swe/2.0";
    /** The XLink namespace, for the ISO 8601 unit reference of {@link Time}. */
    public static final String XLINK_NAMESPACE = "http://www.w3.org/1999/xlink";
    /** Unit reference of calendar time values (SWE Common 2.0, clause 7.2.7). */
    public static final String ISO_8601_UOM = "http://www.opengis.net/def/uom/ISO-8601/0/Gregorian";
    /** Token separator of the text encoding ControlML arrays use. */
    public static final String TOKEN_SEPARATOR = ",";
    /** Block (row) separator of the text encoding ControlML arrays use. */
    public static final String BLOCK_SEPARATOR = " ";

    private Swe() {
    }
}
