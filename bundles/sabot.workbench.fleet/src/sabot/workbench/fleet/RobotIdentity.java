package sabot.workbench.fleet;

import java.util.Arrays;
import java.util.Objects;

/**
 * A robot's identity as it publishes it in its vCard (XEP-0054, fields as in docs/IDENTITY.md): who it is, where it
 * stands, and its inventory as a QR-code image. An immutable snapshot.
 *
 * @param jid          JABBERID, the robot's bare JID; never null
 * @param nickname     NICKNAME, the name operators use; null when the vCard has none
 * @param url          URL, the robot's configuration portal; null when none
 * @param latitude     GEO/LAT in degrees (WGS 84), -90..90; null when unknown (then longitude is null too)
 * @param longitude    GEO/LON in degrees, -180..180; null when unknown
 * @param uid          UID, a {@code urn:uuid:} URN; never null
 * @param category     FN, what kind of device; never null
 * @param manufacturer N/FAMILY; never null
 * @param model        N/GIVEN; null when none
 * @param qrPng        PHOTO: the PNG image of the QR-code inventory (sabot.identity's {@code QrInventory}); null when
 *                     the vCard has no photo
 */
public record RobotIdentity(String jid, String nickname, String url, Double latitude, Double longitude, String uid,
        String category, String manufacturer, String model, byte[] qrPng) {

    public RobotIdentity {
        Objects.requireNonNull(jid, "jid");
        Objects.requireNonNull(uid, "uid");
        Objects.requireNonNull(category, "category");
        Objects.requireNonNull(manufacturer, "manufacturer");
        if ((latitude == null) != (longitude == null)) {
            throw new IllegalArgumentException("latitude and longitude go together");
        }
        qrPng = qrPng == null ? null : qrPng.clone();
    }

    /** @return a copy of the QR-code PNG, or null */
    @Override
    public byte[] qrPng() {
        return qrPng == null ? null : qrPng.clone();
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof RobotIdentity r && r.jid.equals(jid) && Objects.equals(r.nickname, nickname) && Objects
                .equals(r.url, url) && Objects.equals(r.latitude, latitude) && Objects.equals(r.longitude,
                        longitude) && r.uid.equals(uid) && r.category.equals(category) && r.manufacturer.equals(
                                manufacturer) && Objects.equals(r.model, model) && Arrays.equals(r.qrPng, qrPng);
    }

    @Override
    public int hashCode() {
        return Objects.hash(jid, nickname, url, latitude, longitude, uid, category, manufacturer, model) * 31 + Arrays
                .hashCode(qrPng);
    }

    @Override
    public String toString() {
        return "RobotIdentity[" + jid + " " + nickname + " " + uid + (qrPng == null ? " no QR" : " QR "
                + qrPng.length + " bytes") + "]";
    }
}
