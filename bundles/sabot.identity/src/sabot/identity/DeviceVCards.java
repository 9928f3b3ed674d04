package sabot.identity;

import java.net.URI;
import java.time.LocalDate;
import java.time.format.DateTimeParseException;

import java.util.regex.Matcher;
import java.util.regex.Pattern;

import org.jivesoftware.smackx.vcardtemp.packet.VCard;

/**
 * Device profiles in Smack's {@link VCard} (a final class): building one from a {@link DeviceProfile} and reading a
 * profile back, including what Smack's own vCard model does not expose, GEO (LAT/LON), kept as a raw field that
 * {@link sabot.identity.provider.DeviceVCardProvider} fills and {@link #geoOf} reads.
 */
public final class DeviceVCards {

    private static final Pattern GEO = Pattern.compile("<GEO><LAT>([^<]*)</LAT><LON>([^<]*)</LON></GEO>");

    private DeviceVCards() {
    }

    /** @return the vCard of a profile, with the PNG as PHOTO (null for none) */
    public static VCard of(DeviceProfile p, byte[] png) {
        VCard v = new VCard();
        v.setLastName(p.manufacturer());
        if (p.model() != null) {
            v.setFirstName(p.model());
        }
        v.setField("FN", p.category()); // after N: Smack recomputes FN from N in the N setters
        if (p.nickname() != null) {
            v.setNickName(p.nickname());
        }
        if (p.portal() != null) {
            v.setField("URL", p.portal().toString());
        }
        if (p.latitude() != null) {
            setGeo(v, DeviceProfile.geo(p.latitude()), DeviceProfile.geo(p.longitude()));
        }
        v.setField("UID", p.uid());
        v.setJabberId(p.jid());
        v.setField("ROLE", p.role());
        if (p.commissioned() != null) {
            v.setField("BDAY", p.commissioned().toString());
        }
        if (p.description() != null) {
            v.setField("DESC", p.description());
        }
        DeviceProfile.SupportContact s = p.support();
        if (s != null) {
            putAddress(v, "EXTADD", s.organisation());
            putAddress(v, "STREET", s.street());
            putAddress(v, "LOCALITY", s.locality());
            putAddress(v, "PCODE", s.postalCode());
            putAddress(v, "CTRY", s.country());
            if (s.phone() != null) {
                v.setPhoneWork("VOICE", s.phone());
            }
        }
        if (png != null) {
            v.setAvatar(png, "image/png");
        }
        return v;
    }

    private static void putAddress(VCard v, String field, String value) {
        if (value != null) {
            v.setAddressFieldWork(field, value);
        }
    }

    /** Sets GEO, already formatted (six decimals, numbers only: the text is written as XML). */
    public static void setGeo(VCard v, String lat, String lon) {
        if (!lat.matches("-?[0-9]{1,3}(\\.[0-9]{1,9})?") || !lon.matches("-?[0-9]{1,3}(\\.[0-9]{1,9})?")) {
            throw new IllegalArgumentException("GEO must be decimal degrees: " + lat + ", " + lon);
        }
        v.setField("GEO", "<LAT>" + lat + "</LAT><LON>" + lon + "</LON>", true);
    }

    /** @return GEO's LAT and LON as written, or null when the vCard has no GEO */
    public static String[] geoOf(VCard v) {
        Matcher m = GEO.matcher(v.toXML().toString());
        return m.find() ? new String[] { m.group(1), m.group(2) } : null;
    }

    /** @return the device profile in a vCard, or {@link IdentityResult.Problem#NOT_A_DEVICE} */
    public static IdentityResult<DeviceProfile> profileOf(VCard v) {
        String[] geo = geoOf(v);
        String latitude = geo == null ? null : geo[0];
        String longitude = geo == null ? null : geo[1];
        String fn = v.getField("FN");
        String uid = v.getField("UID");
        String role = v.getField("ROLE");
        if (fn == null || v.getLastName() == null || uid == null || role == null || v.getJabberId() == null) {
            return IdentityResult.err(IdentityResult.Problem.NOT_A_DEVICE,
                    "a device vCard needs FN, N/FAMILY, UID, ROLE and JABBERID");
        }
        try {
            Double lat = latitude == null ? null : Double.valueOf(latitude);
            Double lon = longitude == null ? null : Double.valueOf(longitude);
            String url = v.getField("URL");
            String bday = v.getField("BDAY");
            DeviceProfile.SupportContact support = null;
            if (v.getAddressFieldWork("STREET") != null || v.getAddressFieldWork("LOCALITY") != null || v.getPhoneWork(
                    "VOICE") != null || v.getAddressFieldWork("EXTADD") != null) {
                support = new DeviceProfile.SupportContact(v.getAddressFieldWork("EXTADD"), v.getAddressFieldWork(
                        "STREET"), v.getAddressFieldWork("LOCALITY"), v.getAddressFieldWork("PCODE"), v.getAddressFieldWork(
                                "CTRY"), v.getPhoneWork("VOICE"));
            }
            return new IdentityResult.Ok<>(new DeviceProfile(fn, v.getLastName(), v.getFirstName(), v.getNickName(), url
                    == null ? null : URI.create(url), lat, lon, uid, v.getJabberId(), role, bday == null ? null
                            : LocalDate.parse(bday), support, v.getField("DESC")));
        } catch (IllegalArgumentException | DateTimeParseException e) {
            return IdentityResult.err(IdentityResult.Problem.NOT_A_DEVICE, "bad device field: " + e.getMessage());
        }
    }
}
