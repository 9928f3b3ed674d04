package sabot.identity;

import java.net.URI;
import java.time.LocalDate;
import java.util.Locale;
import java.util.Objects;

/**
 * A device's vCard-temp (XEP-0054) profile, following the thesis's rules for the fields:
 * <table>
 * <caption>vCard fields</caption>
 * <tr><td>FN</td><td>{@link #category} (what kind of device)</td></tr>
 * <tr><td>N/FAMILY, N/GIVEN</td><td>{@link #manufacturer}, {@link #model}</td></tr>
 * <tr><td>NICKNAME</td><td>{@link #nickname}, the name operators use</td></tr>
 * <tr><td>URL</td><td>{@link #portal}, the configuration portal</td></tr>
 * <tr><td>GEO</td><td>{@link #latitude}, {@link #longitude}, written to six decimals (about 0.1 m)</td></tr>
 * <tr><td>UID</td><td>{@link #uid}, {@code urn:uuid:} with the {@link DeviceUrn version-5 UUID} of the serial</td></tr>
 * <tr><td>JABBERID</td><td>{@link #jid}</td></tr>
 * <tr><td>ROLE</td><td>{@link #role}, e.g. {@code robot}, {@code workbench}</td></tr>
 * <tr><td>BDAY</td><td>{@link #commissioned}, the day the device entered service</td></tr>
 * <tr><td>ADR, TEL (WORK)</td><td>{@link #support}, whom to call</td></tr>
 * <tr><td>DESC</td><td>{@link #description}</td></tr>
 * <tr><td>PHOTO</td><td>the PNG QR code of the {@link Inventory} (see {@link QrInventory})</td></tr>
 * </table>
 *
 * @param category     FN; never null
 * @param manufacturer N/FAMILY; never null
 * @param model        N/GIVEN; may be null
 * @param nickname     NICKNAME; may be null
 * @param portal       URL; may be null
 * @param latitude     GEO/LAT in degrees (WGS 84), -90..90; null when unknown (then longitude is null too)
 * @param longitude    GEO/LON in degrees, -180..180; null when unknown
 * @param uid          UID, a {@code urn:uuid:} URN; never null
 * @param jid          JABBERID, the device's bare JID; never null
 * @param role         ROLE; never null
 * @param commissioned BDAY; may be null
 * @param support      ADR + TEL; may be null
 * @param description  DESC; may be null
 */
public record DeviceProfile(String category, String manufacturer, String model, String nickname, URI portal,
        Double latitude, Double longitude, String uid, String jid, String role, LocalDate commissioned,
        SupportContact support, String description) {

    /**
     * Whom to call about the device (vCard ADR and TEL, WORK).
     *
     * @param organisation ADR/EXTADD; may be null
     * @param street       ADR/STREET; may be null
     * @param locality     ADR/LOCALITY; may be null
     * @param postalCode   ADR/PCODE; may be null
     * @param country      ADR/CTRY; may be null
     * @param phone        TEL/NUMBER (voice); may be null
     */
    public record SupportContact(String organisation, String street, String locality, String postalCode,
            String country, String phone) {
    }

    public DeviceProfile {
        Objects.requireNonNull(category, "category");
        Objects.requireNonNull(manufacturer, "manufacturer");
        Objects.requireNonNull(jid, "jid");
        Objects.requireNonNull(role, "role");
        if (DeviceUrn.parseUrn(uid) == null) {
            throw new IllegalArgumentException("uid must be a urn:uuid: URN, was " + uid);
        }
        if ((latitude == null) != (longitude == null)) {
            throw new IllegalArgumentException("latitude and longitude go together");
        }
        if (latitude != null) {
            // GEO carries six decimals: round here so that what is published is what is read back
            latitude = round6(latitude);
            longitude = round6(longitude);
            if (!(latitude >= -90 && latitude <= 90 && longitude >= -180 && longitude <= 180)) {
                throw new IllegalArgumentException("GEO out of range: " + latitude + ", " + longitude);
            }
        }
    }

    /** @return the value rounded to six decimals (about 0.11 m of latitude) */
    public static double round6(double degrees) {
        return Double.parseDouble(geo(degrees));
    }

    /** @return the GEO text of a coordinate: six decimals, '.' as separator */
    public static String geo(double degrees) {
        return String.format(Locale.ROOT, "%.6f", degrees);
    }
}
