package sabot.controlml;

import java.time.Instant;
import java.util.Objects;
import java.util.regex.Pattern;

import javax.xml.namespace.QName;

import org.jivesoftware.smack.packet.ExtensionElement;
import org.jivesoftware.smack.packet.StanzaError;
import org.jivesoftware.smack.packet.XmlEnvironment;

import sabot.controlml.payload.PayloadException;
import sabot.controlml.swe.IsoInstant;
import sabot.controlml.swe.RecordTemplate;
import sabot.controlml.swe.SweComponent;
import sabot.controlml.swe.SweXml;

/**
 * The {@code <control-ml/>} element, immutable. Built by the factory methods for sending, or by
 * {@link sabot.controlml.provider.ControlMlElementProvider} when received.
 * <p>
 * A received element the reader could not accept is still an element: {@link #defect()} says what was wrong (an
 * error value to answer with), and the attributes it could read are kept for the answer. The reader never throws
 * for ControlML-level problems, so a bad request cannot break the XMPP connection that carried it.
 */
public final class ControlMlElement implements ExtensionElement {

    /** The qualified name (Smack looks extension classes up by it). */
    public static final QName QNAME = new QName(ControlMl.NAMESPACE, ControlMl.ELEMENT);

    /** Syntax of {@code res}: {@code cm} and dot-separated lower-case words, e.g. {@code cm.fs.read}. */
    public static final Pattern RESOURCE_SYNTAX = Pattern.compile("cm(\\.[a-z][a-z0-9-]{0,30}){1,4}");

    private final ControlMlType type;
    private final RequestId id;
    private final String res;
    private final SweComponent payload;
    private final ControlMlError failure;
    private final ControlMlError defect;
    /** A set's send time on the requester's clock ({@code sent}), or null. */
    private final Instant sent;
    /** Write the payload in the text form when the resource has a record structure and the value fits it. */
    private final boolean textForm;
    /**
     * A received result's payload decoded by its resource's codec while it was read: decoded on the thread that built
     * the payload, where it is still in cache, and not on the thread that waits for the answer (measured: ~10 us of a
     * 0.4 ms round trip otherwise).
     */
    private final Decoded<?> decoded;
    /** {@link #contentXml()} once computed (an element is immutable). */
    private volatile String content;

    private ControlMlElement(ControlMlType type, RequestId id, String res, SweComponent payload,
            ControlMlError failure, ControlMlError defect) {
        this(type, id, res, payload, failure, defect, defect == null);
    }

    private ControlMlElement(ControlMlType type, RequestId id, String res, SweComponent payload,
            ControlMlError failure, ControlMlError defect, boolean textForm) {
        this(type, id, res, payload, failure, defect, textForm, Decoded.NONE);
    }

    private ControlMlElement(ControlMlType type, RequestId id, String res, SweComponent payload,
            ControlMlError failure, ControlMlError defect, boolean textForm, Decoded<?> decoded) {
        this(type, id, res, payload, failure, defect, textForm, decoded, null);
    }

    private ControlMlElement(ControlMlType type, RequestId id, String res, SweComponent payload,
            ControlMlError failure, ControlMlError defect, boolean textForm, Decoded<?> decoded, Instant sent) {
        this.sent = sent;
        this.decoded = decoded;
        this.textForm = textForm;
        this.type = type;
        this.id = id;
        this.res = res;
        this.payload = payload;
        this.failure = failure;
        this.defect = defect;
    }

    /**
     * @param type    get or set
     * @param id      a fresh id of the requester
     * @param res     resource name, matching {@link #RESOURCE_SYNTAX}
     * @param payload the value of a set, the query of a get on a resource that takes one, else null
     * @return a request element
     */
    public static ControlMlElement request(ControlMlType type, RequestId id, String res, SweComponent payload) {
        if (!type.isRequest()) {
            throw new IllegalArgumentException("not a request type: " + type);
        }
        return new ControlMlElement(type, Objects.requireNonNull(id), checkRes(res), payload, null, null);
    }

    /** @return a result (answer to a request, or a telemetry item); payload null for a bare acknowledgement */
    public static ControlMlElement result(RequestId id, String res, SweComponent payload) {
        return new ControlMlElement(ControlMlType.RESULT, Objects.requireNonNull(id), checkRes(res), payload, null,
                null);
    }

    /** @return an error answer */
    public static ControlMlElement error(RequestId id, String res, ControlMlError failure) {
        return new ControlMlElement(ControlMlType.ERROR, Objects.requireNonNull(id), checkRes(res), null,
                Objects.requireNonNull(failure), null);
    }

    /**
     * For providers: an element as read. Exactly one of the readable parts may be missing when {@code defect} is
     * set.
     */
    public static ControlMlElement received(ControlMlType type, RequestId id, String res, SweComponent payload,
            ControlMlError failure, ControlMlError defect) {
        return received(type, id, res, payload, failure, defect, null);
    }

    /** For providers: an element as read, with a set's send time ({@code sent}, null when absent). */
    public static ControlMlElement received(ControlMlType type, RequestId id, String res, SweComponent payload,
            ControlMlError failure, ControlMlError defect, Instant sent) {
        // Section 4's resources only: Smack's reader is process-wide and knows no connection's registry. A result of
        // a registered resource of another bundle is decoded by value() on the thread that asked for it.
        Resource<?, ?> resource = type == ControlMlType.RESULT && defect == null && payload != null ? Resources.byName(
                res) : null;
        Decoded<?> decoded = resource == null ? Decoded.NONE : Decoded.of(resource, payload);
        return new ControlMlElement(type, id, res, payload, failure, defect, false, decoded, sent);
    }

    /** What a received result's payload decoded to while it was read. */
    private sealed interface Decoded<T> {

        /** Not decoded while read: not a result, no payload, or not a resource of section 4. */
        None NONE = new None();

        /** Nothing decoded. */
        record None() implements Decoded<Object> {
        }

        /** The value; never null. */
        record Value<T>(T value) implements Decoded<T> {
        }

        /** The payload does not fit the resource's schema: the condition and text to answer with. */
        record Failure(ControlMlCondition condition, String text) implements Decoded<Object> {
        }

        static <T> Decoded<?> of(Resource<T, ?> resource, SweComponent payload) {
            try {
                return new Value<>(resource.codec().decode(payload));
            } catch (PayloadException e) {
                return new Failure(e.error().cmCondition(), e.error().text());
            } catch (RuntimeException e) {
                // a codec bug must not take the reader thread down: the payload is unreadable
                return new Failure(ControlMlCondition.MALFORMED_PAYLOAD, "unreadable payload: " + e);
            }
        }
    }

    /**
     * @return the payload decoded by {@code resource}'s codec; for a received result of that resource, the value
     *         decoded when it was read
     * @throws PayloadException when the payload does not fit the resource's schema
     * @throws IllegalStateException when there is no payload
     */
    public <T> T value(Resource<T, ?> resource) throws PayloadException {
        if (payload == null) {
            throw new IllegalStateException("no payload");
        }
        if (resource == Resources.byName(res)) {
            switch (decoded) {
                case Decoded.Value<?> v -> {
                    @SuppressWarnings("unchecked") // decoded by the codec of the resource of this name
                    T value = (T) v.value();
                    return value;
                }
                case Decoded.Failure f -> throw new PayloadException(f.condition(), f.text());
                case Decoded.None none -> {
                    // not decoded while read: decode now
                }
            }
        }
        return resource.codec().decode(payload);
    }

    /**
     * @param text true (the default of the factory methods): a payload of a resource with a record structure that
     *             fits it is written in the text form (a {@code DataStream} referring to the structure, see
     *             {@link Resource#recordTemplate()}); false: always the XML form (a DataRecord with an element per
     *             field). Received elements are written in the XML form. Readers accept both.
     * @return this element with that payload form; equal to this one
     */
    public ControlMlElement withTextForm(boolean text) {
        return text == textForm ? this : new ControlMlElement(type, id, res, payload, failure, defect, text, decoded,
                sent);
    }

    /**
     * @param time when the requester sends this set, on its clock (section 1's {@code sent}); null for none
     * @return this set carrying that send time
     * @throws IllegalStateException when this is not a set
     */
    public ControlMlElement withSent(Instant time) {
        if (type != ControlMlType.SET) {
            throw new IllegalStateException("only a set carries a send time, not a " + type);
        }
        return new ControlMlElement(type, id, res, payload, failure, defect, textForm, decoded, time);
    }

    /** @return a set's send time on the requester's clock ({@code sent}), or null when it carries none */
    public Instant sent() {
        return sent;
    }

    /** @return true when the payload is written in the text form where its resource allows it */
    public boolean isTextForm() {
        return textForm;
    }

    /**
     * @return whether {@code res} matches {@link #RESOURCE_SYNTAX}; a catalogue resource's name does, found without
     *         running the expression (it is met on every element read and written)
     */
    public static boolean isResourceName(String res) {
        return res != null && (Resources.byName(res) != null || RESOURCE_SYNTAX.matcher(res).matches());
    }

    private static String checkRes(String res) {
        if (!isResourceName(res)) {
            throw new IllegalArgumentException("not a resource name: " + res);
        }
        return res;
    }

    /** @return the type; null only on a defective element whose type could not be read */
    public ControlMlType type() {
        return type;
    }

    /** @return the id; null only on a defective element whose id could not be read */
    public RequestId id() {
        return id;
    }

    /** @return the resource name; null only on a defective element whose res could not be read */
    public String res() {
        return res;
    }

    /** @return the payload, or null when there is none */
    public SweComponent payload() {
        return payload;
    }

    /** @return the failure of an error answer, or null */
    public ControlMlError failure() {
        return failure;
    }

    /** @return what made a received element unacceptable, or null when it is well-formed ControlML */
    public ControlMlError defect() {
        return defect;
    }

    /** @return true when the attributes could all be read, so an answer can echo them */
    public boolean hasValidAttributes() {
        return type != null && id != null && res != null;
    }

    @Override
    public String getElementName() {
        return ControlMl.ELEMENT;
    }

    @Override
    public String getNamespace() {
        return ControlMl.NAMESPACE;
    }

    @Override
    public CharSequence toXML(XmlEnvironment xmlEnvironment) {
        StringBuilder sb = new StringBuilder(payload == null ? 128 : 1024);
        sb.append("<control-ml xmlns='").append(ControlMl.NAMESPACE).append('\'');
        appendAttributesAndContent(sb);
        return sb;
    }

    /** Appends {@code type='..' id='..' res='..'} and then either {@code />} or {@code >content</control-ml>}. */
    public void appendAttributesAndContent(StringBuilder sb) {
        appendAttributes(sb);
        String content = contentXml();
        if (content.isEmpty()) {
            sb.append("/>");
        } else {
            sb.append('>').append(content).append("</control-ml>");
        }
    }

    /** Appends the attributes, each preceded by a space. */
    public void appendAttributes(StringBuilder sb) {
        if (type != null) {
            sb.append(" type='").append(type.attribute()).append('\'');
        }
        if (id != null) {
            sb.append(" id='").append(id).append('\'');
        }
        if (res != null) {
            sb.append(" res='").append(res).append('\'');
        }
        if (sent != null) {
            sb.append(" sent='");
            IsoInstant.format(sent, sb);
            sb.append('\'');
        }
    }

    /**
     * @return the element's content (payload or failure) as XML, or the empty string; computed once (the device
     *         computes it on the thread that made the answer, where the payload is still in cache)
     */
    public String contentXml() {
        String xml = content;
        if (xml == null) {
            xml = writeContent();
            content = xml;
        }
        return xml;
    }

    private String writeContent() {
        StringBuilder sb = new StringBuilder();
        if (payload != null) {
            Resource<?, ?> resource = textForm ? Resources.byName(res) : null;
            RecordTemplate template = resource == null ? null : resource.recordTemplate();
            if (template != null && template.fits(payload)) {
                SweXml.writeStream(resource.recordHref(), template, payload, sb);
            } else {
                SweXml.write(payload, sb);
            }
        }
        if (failure != null) {
            sb.append("<failure condition='").append(failure.condition()).append("' reason='").append(failure
                    .cmCondition().element()).append('\'');
            if (failure.text().isEmpty()) {
                sb.append("/>");
            } else {
                sb.append('>');
                SweXml.escape(failure.text(), sb);
                sb.append("</failure>");
            }
        }
        return sb.toString();
    }

    /** @return the RFC 6120 condition for a failure element's {@code condition} attribute, or null */
    public static StanzaError.Condition conditionFromAttribute(String value) {
        try {
            return value == null ? null : StanzaError.Condition.fromString(value);
        } catch (IllegalArgumentException e) {
            return null;
        }
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof ControlMlElement e && type == e.type && Objects.equals(id, e.id) && Objects.equals(res,
                e.res) && Objects.equals(payload, e.payload) && Objects.equals(failure, e.failure) && Objects
                        .equals(defect, e.defect) && Objects.equals(sent, e.sent);
    }

    @Override
    public int hashCode() {
        return Objects.hash(type, id, res, payload, failure, defect, sent);
    }

    @Override
    public String toString() {
        return "control-ml[" + type + " " + id + " " + res + (sent == null ? "" : " sent=" + sent) + (payload == null ? "" : " +payload") + (failure == null
                ? "" : " failure=" + failure) + (defect == null ? "" : " defect=" + defect) + "]";
    }
}
