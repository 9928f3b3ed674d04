package sabot.identity.provider;

import java.io.IOException;

import org.jivesoftware.smack.packet.XmlEnvironment;
import org.jivesoftware.smack.provider.IQProvider;
import org.jivesoftware.smack.xml.XmlPullParser;
import org.jivesoftware.smack.xml.XmlPullParserException;

import org.jivesoftware.smackx.vcardtemp.packet.VCard;

import sabot.identity.DeviceVCards;

/**
 * Reads vcard-temp into Smack's {@link VCard}: every field Smack's own provider reads, plus GEO (kept as a raw
 * field, see {@link DeviceVCards#geoOf}), and FN as written (Smack's VCard recomputes FN whenever an N part is set,
 * so FN is applied after the whole card is read). Registered in place of Smack's provider by
 * {@link sabot.identity.DeviceIdentityManager}; it returns the same class, so {@code VCardManager} users are
 * unaffected. GEO values that are not decimal degrees are dropped.
 */
public final class DeviceVCardProvider extends IQProvider<VCard> {

    @Override
    public VCard parse(XmlPullParser parser, int initialDepth, XmlEnvironment xmlEnvironment)
            throws XmlPullParserException, IOException {
        VCard card = new VCard();
        String fn = null;
        while (true) {
            XmlPullParser.Event e = parser.next();
            if (e == XmlPullParser.Event.END_ELEMENT && parser.getDepth() == initialDepth) {
                break;
            }
            if (e != XmlPullParser.Event.START_ELEMENT) {
                continue;
            }
            String name = parser.getName();
            int depth = parser.getDepth();
            switch (name) {
                case "N" -> {
                    for (String[] kv : fields(parser, depth)) {
                        switch (kv[0]) {
                            case "FAMILY" -> card.setLastName(kv[1]);
                            case "GIVEN" -> card.setFirstName(kv[1]);
                            case "MIDDLE" -> card.setMiddleName(kv[1]);
                            case "PREFIX" -> card.setPrefix(kv[1]);
                            case "SUFFIX" -> card.setSuffix(kv[1]);
                            default -> { }
                        }
                    }
                }
                case "ORG" -> {
                    for (String[] kv : fields(parser, depth)) {
                        if ("ORGNAME".equals(kv[0])) {
                            card.setOrganization(kv[1]);
                        } else if ("ORGUNIT".equals(kv[0])) {
                            card.setOrganizationUnit(kv[1]);
                        }
                    }
                }
                case "GEO" -> {
                    String lat = null;
                    String lon = null;
                    for (String[] kv : fields(parser, depth)) {
                        if ("LAT".equals(kv[0])) {
                            lat = kv[1].strip();
                        } else if ("LON".equals(kv[0])) {
                            lon = kv[1].strip();
                        }
                    }
                    if (lat != null && lon != null) {
                        try {
                            DeviceVCards.setGeo(card, lat, lon);
                        } catch (IllegalArgumentException notDegrees) {
                            // not decimal degrees: not ours to guess
                        }
                    }
                }
                case "ADR" -> {
                    java.util.List<String[]> kvs = fields(parser, depth);
                    boolean home = kvs.stream().anyMatch(kv -> "HOME".equals(kv[0]));
                    for (String[] kv : kvs) {
                        if (!kv[1].isEmpty()) {
                            if (home) {
                                card.setAddressFieldHome(kv[0], kv[1]);
                            } else {
                                card.setAddressFieldWork(kv[0], kv[1]);
                            }
                        }
                    }
                }
                case "TEL" -> {
                    java.util.List<String[]> kvs = fields(parser, depth);
                    boolean home = kvs.stream().anyMatch(kv -> "HOME".equals(kv[0]));
                    String label = "VOICE";
                    String number = null;
                    for (String[] kv : kvs) {
                        if ("NUMBER".equals(kv[0])) {
                            number = kv[1];
                        } else if (!"HOME".equals(kv[0]) && !"WORK".equals(kv[0]) && kv[1].isEmpty()) {
                            label = kv[0];
                        }
                    }
                    if (number != null) {
                        if (home) {
                            card.setPhoneHome(label, number);
                        } else {
                            card.setPhoneWork(label, number);
                        }
                    }
                }
                case "EMAIL" -> {
                    java.util.List<String[]> kvs = fields(parser, depth);
                    boolean work = kvs.stream().anyMatch(kv -> "WORK".equals(kv[0]));
                    for (String[] kv : kvs) {
                        if ("USERID".equals(kv[0])) {
                            if (work) {
                                card.setEmailWork(kv[1]);
                            } else {
                                card.setEmailHome(kv[1]);
                            }
                        }
                    }
                }
                case "PHOTO" -> {
                    String type = null;
                    String binval = null;
                    for (String[] kv : fields(parser, depth)) {
                        if ("TYPE".equals(kv[0])) {
                            type = kv[1];
                        } else if ("BINVAL".equals(kv[0])) {
                            binval = kv[1].replaceAll("\\s", "");
                        }
                    }
                    if (type != null && binval != null) {
                        card.setAvatar(binval, type);
                    }
                }
                default -> {
                    String text = simpleText(parser, depth);
                    if (text == null) {
                        break;
                    }
                    if ("FN".equals(name)) {
                        fn = text;
                    } else if ("NICKNAME".equals(name)) {
                        card.setNickName(text);
                    } else if ("JABBERID".equals(name)) {
                        card.setJabberId(text);
                    } else {
                        card.setField(name, text);
                    }
                }
            }
        }
        if (fn != null) {
            card.setField("FN", fn);
        }
        return card;
    }

    /** The child elements of a structured field as (name, text) pairs; the parser ends on the field's end tag. */
    private static java.util.List<String[]> fields(XmlPullParser parser, int depth) throws XmlPullParserException,
            IOException {
        java.util.List<String[]> out = new java.util.ArrayList<>();
        while (true) {
            XmlPullParser.Event e = parser.next();
            if (e == XmlPullParser.Event.END_ELEMENT && parser.getDepth() == depth) {
                return out;
            }
            if (e == XmlPullParser.Event.START_ELEMENT && parser.getDepth() == depth + 1) {
                String child = parser.getName();
                String text = simpleText(parser, depth + 1);
                out.add(new String[] { child, text == null ? "" : text });
            }
        }
    }

    /** Text of an element without children, or null (the element is then skipped); ends on its end tag. */
    private static String simpleText(XmlPullParser parser, int depth) throws XmlPullParserException, IOException {
        StringBuilder text = new StringBuilder();
        boolean children = false;
        while (true) {
            XmlPullParser.Event e = parser.next();
            if (e == XmlPullParser.Event.END_ELEMENT && parser.getDepth() == depth) {
                return children ? null : text.toString();
            }
            if (e == XmlPullParser.Event.START_ELEMENT) {
                children = true;
            } else if (e == XmlPullParser.Event.TEXT_CHARACTERS) {
                text.append(parser.getText());
            }
        }
    }
}
