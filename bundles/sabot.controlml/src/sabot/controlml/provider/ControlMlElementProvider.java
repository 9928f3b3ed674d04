package sabot.controlml.provider;

import java.io.IOException;
import java.time.Instant;
import java.time.format.DateTimeParseException;

import org.jivesoftware.smack.packet.StanzaError;
import org.jivesoftware.smack.packet.XmlEnvironment;
import org.jivesoftware.smack.provider.ExtensionElementProvider;
import org.jivesoftware.smack.xml.XmlPullParser;
import org.jivesoftware.smack.xml.XmlPullParserException;

import sabot.controlml.ControlMl;
import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlError;
import sabot.controlml.ControlMlType;
import sabot.controlml.RequestId;
import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.swe.IsoInstant;
import sabot.controlml.swe.Swe;
import sabot.controlml.swe.RecordTemplate;
import sabot.controlml.swe.SweComponent;
import sabot.controlml.swe.SweFormatException;
import sabot.controlml.swe.SweXml;

/**
 * Reads {@code <control-ml/>} (in messages and PEP items; {@link ControlMlIQProvider} delegates here for IQs).
 * <p>
 * Strict and total: every ControlML-level problem (attributes missing, extra or invalid, a bad id, content that is
 * not one SWE component, a payload over {@link ControlMl#MAX_PAYLOAD_CHARS}, a bad failure element) becomes the
 * element's {@link ControlMlElement#defect() defect}, the rest of the element is skipped, and the parser is left on
 * the element's end tag as Smack requires. Only XML that is not well-formed (which a server never forwards) makes
 * the underlying parser throw.
 */
public final class ControlMlElementProvider extends ExtensionElementProvider<ControlMlElement> {

    @Override
    public ControlMlElement parse(XmlPullParser parser, int initialDepth, XmlEnvironment xmlEnvironment)
            throws XmlPullParserException, IOException {
        return parseElement(parser, initialDepth);
    }

    /**
     * @param parser       positioned on the {@code control-ml} start tag
     * @param initialDepth the parser's depth there
     * @return the element, possibly with a defect; the parser is on its end tag
     */
    public static ControlMlElement parseElement(XmlPullParser parser, int initialDepth) throws XmlPullParserException,
            IOException {
        Attributes attributes = readAttributes(parser);
        if (attributes.defect() != null) {
            skipToEnd(parser, initialDepth);
            return ControlMlElement.received(attributes.type(), attributes.id(), attributes.res(), null, null,
                    attributes.defect(), null);
        }
        Content content = new Content(attributes.type(), attributes.res());
        ControlMlError defect = content.read(parser, initialDepth);
        if (defect != null) {
            skipToEnd(parser, initialDepth);
        }
        return ControlMlElement.received(attributes.type(), attributes.id(), attributes.res(), defect == null
                ? content.payload : null, content.failure, defect, attributes.sent());
    }

    /**
     * The attributes as far as they could be read, and the first problem with them.
     *
     * @param res  null when absent or not a resource name
     * @param sent a set's send time, null when absent
     */
    private record Attributes(ControlMlType type, RequestId id, String res, Instant sent, ControlMlError defect) {
    }

    private static Attributes readAttributes(XmlPullParser parser) {
        ControlMlError defect = null;
        String typeText = null;
        String idText = null;
        String res = null;
        String sentText = null;
        for (int i = 0; i < parser.getAttributeCount(); i++) {
            String name = parser.getAttributeName(i);
            String value = parser.getAttributeValue(i);
            if (!SweXml.noNamespace(parser.getAttributeNamespace(i))) {
                defect = first(defect, ControlMlCondition.BAD_ATTRIBUTES, "unexpected attribute " + name);
                continue;
            }
            switch (name) {
                case "type" -> typeText = value;
                case "id" -> idText = value;
                case "res" -> res = value;
                case "sent" -> sentText = value;
                default -> defect = first(defect, ControlMlCondition.BAD_ATTRIBUTES, "unexpected attribute "
                        + abbreviate(name) + " (control-ml has type, id, res and, on a set, sent)");
            }
        }
        if (typeText == null || idText == null || res == null) {
            defect = first(defect, ControlMlCondition.BAD_ATTRIBUTES, "missing attribute"
                    + (typeText == null ? " type" : "") + (idText == null ? " id" : "") + (res == null ? " res" : ""));
        }
        ControlMlType type = null;
        if (typeText != null) {
            type = ControlMlType.fromAttribute(typeText);
            if (type == null) {
                defect = first(defect, ControlMlCondition.BAD_ATTRIBUTES, "type must be get, set, result or error, not '"
                        + abbreviate(typeText) + "'");
            }
        }
        RequestId id = null;
        if (idText != null) {
            id = RequestId.parse(idText);
            if (id == null) {
                defect = first(defect, ControlMlCondition.BAD_ID, "id must be YYYYMMDD:UINT32, not '" + abbreviate(
                        idText) + "'");
            }
        }
        if (res != null && !ControlMlElement.isResourceName(res)) {
            defect = first(defect, ControlMlCondition.BAD_ATTRIBUTES, "res '" + abbreviate(res)
                    + "' is not a resource name (cm.<name>)");
            res = null;
        }
        Instant sent = null;
        if (sentText != null) {
            if (type != ControlMlType.SET) {
                defect = first(defect, ControlMlCondition.BAD_ATTRIBUTES, "sent belongs on a set only");
            } else {
                sent = readSent(sentText);
                if (sent == null) {
                    defect = first(defect, ControlMlCondition.BAD_ATTRIBUTES, "sent must be an ISO 8601 UTC time"
                            + " stamp (2026-11-28T10:15:30.125Z), not '" + abbreviate(sentText) + "'");
                }
            }
        }
        return new Attributes(type, id, res, sent, defect);
    }

    /** @return the send time, or null when the text is not a UTC time stamp of section 3's form */
    private static Instant readSent(String text) {
        if (text.isEmpty() || text.charAt(text.length() - 1) != 'Z') {
            return null; // Instant.parse would take an offset; the protocol's time stamps are UTC
        }
        try {
            return IsoInstant.parse(text);
        } catch (DateTimeParseException e) {
            return null;
        }
    }

    /** Reads the content of an element whose attributes were all readable: one payload, or an error's failure. */
    private static final class Content {
        private final ControlMlType type;
        private final String res;
        private final SweXml.Budget budget = new SweXml.Budget(ControlMl.MAX_PAYLOAD_CHARS);
        private SweComponent payload;
        private ControlMlError failure;

        Content(ControlMlType type, String res) {
            this.type = type;
            this.res = res;
        }

        /** @return the content's first defect, or null; the parser is on the element's end tag when null */
        ControlMlError read(XmlPullParser parser, int initialDepth) throws XmlPullParserException, IOException {
            ControlMlError defect;
            try {
                defect = readChildren(parser, initialDepth);
            } catch (SweFormatException e) {
                return ControlMlError.of(e.problem() == SweFormatException.Problem.TOO_LARGE
                        ? ControlMlCondition.PAYLOAD_TOO_LARGE : ControlMlCondition.MALFORMED_PAYLOAD, e.getMessage());
            } catch (RuntimeException e) {
                // A reader bug must not take the connection down: report it as a malformed payload.
                return ControlMlError.of(ControlMlCondition.MALFORMED_PAYLOAD, "unreadable payload: " + e);
            }
            if (defect != null) {
                return defect;
            }
            if (type == ControlMlType.ERROR && failure == null) {
                return ControlMlError.of(ControlMlCondition.MALFORMED_PAYLOAD, "an error answer needs a failure");
            }
            if (type != ControlMlType.ERROR && failure != null) {
                return ControlMlError.of(ControlMlCondition.MALFORMED_PAYLOAD, "failure only in error answers");
            }
            return null;
        }

        /** @return the first defect, or null at the element's end tag */
        private ControlMlError readChildren(XmlPullParser parser, int initialDepth) throws SweFormatException,
                XmlPullParserException, IOException {
            while (true) {
                switch (parser.next()) {
                    case START_ELEMENT -> {
                        ControlMlError defect = readChild(parser);
                        if (defect != null) {
                            return defect;
                        }
                    }
                    case END_ELEMENT -> {
                        if (parser.getDepth() == initialDepth) {
                            return null;
                        }
                    }
                    case TEXT_CHARACTERS, ENTITY_REFERENCE -> {
                        if (!parser.getText().isBlank()) {
                            return ControlMlError.of(ControlMlCondition.MALFORMED_PAYLOAD,
                                    "text where a payload element belongs");
                        }
                    }
                    case END_DOCUMENT -> throw new XmlPullParserException("document ended inside control-ml");
                    default -> {
                        // whitespace, comments
                    }
                }
            }
        }

        /** @return the defect of the child element the parser is on, or null when it was read */
        private ControlMlError readChild(XmlPullParser parser) throws SweFormatException, XmlPullParserException,
                IOException {
            if (Swe.NAMESPACE.equals(parser.getNamespace())) {
                if (payload != null || failure != null) {
                    return ControlMlError.of(ControlMlCondition.MALFORMED_PAYLOAD,
                            "control-ml holds at most one payload component");
                }
                payload = SweXml.readPayload(parser, budget, href -> structureOf(res, href));
                return null;
            }
            if (ControlMl.NAMESPACE.equals(parser.getNamespace()) && "failure".equals(parser.getName())
                    && type == ControlMlType.ERROR && failure == null && payload == null) {
                failure = readFailure(parser);
                return failure != null ? null : ControlMlError.of(ControlMlCondition.MALFORMED_PAYLOAD,
                        "failure needs condition and reason attributes and text only");
            }
            return ControlMlError.of(ControlMlCondition.MALFORMED_PAYLOAD, "unexpected element " + abbreviate(parser
                    .getName()) + " in namespace '" + abbreviate(String.valueOf(parser.getNamespace())) + "'");
        }
    }

    /**
     * The record structure a text-form payload of {@code res} may refer to: that resource's own, by its href. Only
     * section 4's resources have one (resources of other bundles always travel in the XML form), so this reader, which
     * Smack shares between all connections of the process, needs no connection's registry.
     */
    private static RecordTemplate structureOf(String res, String href) {
        Resource<?, ?> resource = res == null ? null : Resources.byName(res);
        return resource != null && href.equals(resource.recordHref()) ? resource.recordTemplate() : null;
    }

    private static ControlMlError readFailure(XmlPullParser parser) throws XmlPullParserException, IOException {
        StanzaError.Condition condition = null;
        ControlMlCondition reason = null;
        for (int i = 0; i < parser.getAttributeCount(); i++) {
            switch (parser.getAttributeName(i)) {
                case "condition" -> condition = ControlMlElement.conditionFromAttribute(parser.getAttributeValue(i));
                case "reason" -> reason = ControlMlCondition.fromElement(parser.getAttributeValue(i));
                default -> {
                    return null;
                }
            }
        }
        int depth = parser.getDepth();
        StringBuilder text = new StringBuilder();
        while (true) {
            XmlPullParser.Event e = parser.next();
            if (e == XmlPullParser.Event.END_ELEMENT && parser.getDepth() == depth) {
                break;
            }
            if (e == XmlPullParser.Event.START_ELEMENT) {
                skipToEnd(parser, parser.getDepth());
                return null;
            }
            if (e == XmlPullParser.Event.TEXT_CHARACTERS || e == XmlPullParser.Event.ENTITY_REFERENCE) {
                text.append(parser.getText());
                if (text.length() > 4096) {
                    return null;
                }
            }
            if (e == XmlPullParser.Event.END_DOCUMENT) {
                throw new XmlPullParserException("document ended inside failure");
            }
        }
        if (condition == null || reason == null) {
            return null;
        }
        return new ControlMlError(condition, reason, text.toString());
    }

    /** Advances to the end tag at {@code depth} (the current element's, if the parser is on a start tag there). */
    static void skipToEnd(XmlPullParser parser, int depth) throws XmlPullParserException, IOException {
        if (parser.getEventType() == XmlPullParser.Event.END_ELEMENT && parser.getDepth() == depth) {
            return;
        }
        while (true) {
            XmlPullParser.Event e = parser.next();
            if (e == XmlPullParser.Event.END_ELEMENT && parser.getDepth() == depth) {
                return;
            }
            if (e == XmlPullParser.Event.END_DOCUMENT) {
                throw new XmlPullParserException("document ended inside control-ml");
            }
        }
    }

    private static ControlMlError first(ControlMlError existing, ControlMlCondition condition, String text) {
        return existing != null ? existing : ControlMlError.of(condition, text);
    }

    private static String abbreviate(String s) {
        return s.length() <= 40 ? s : s.substring(0, 40) + "...";
    }
}
