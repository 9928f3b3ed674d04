package sabot.controlml;

import java.util.Objects;

import org.jivesoftware.smack.packet.ExtensionElement;
import org.jivesoftware.smack.packet.StanzaError;
import org.jivesoftware.smack.packet.XmlEnvironment;

import sabot.controlml.swe.SweXml;

/**
 * The RFC 6120 {@code <text xmlns='urn:ietf:params:xml:ns:xmpp-stanzas' xml:lang='en'/>} of a stanza error,
 * written as a literal so that it keeps its namespace on the wire.
 * <p>
 * Why not {@code StanzaError.Builder#setDescriptiveEnText}: Smack 4.4.8 writes the condition element and the text
 * into one {@code XmlStringBuilder}, each with its own {@code xmlns='urn:ietf:params:xml:ns:xmpp-stanzas'}. When
 * the connection writes the stanza ({@code XmlStringBuilder.write(Writer, XmlEnvironment)}, which uses
 * {@code appendXmlTo}), every emitted {@code xmlns} is taken as the namespace of all that follows in the builder,
 * so the text's (equal) {@code xmlns} is dropped as "redundant" although the text is a <em>sibling</em> of the
 * condition, not its child. The text then goes out as {@code <text xml:lang='en'>} in {@code jabber:client}, and
 * every receiver (Smack's {@code PacketParserUtils.parseError} included) sees an unknown element instead of the
 * descriptive text. {@code toXML()} without an environment does not show the bug; only the real writer does. A
 * literal string is appended verbatim, with its namespace.
 */
final class DescriptiveText implements ExtensionElement {

    static final String ELEMENT = "text";

    private final String text;

    DescriptiveText(String text) {
        this.text = Objects.requireNonNull(text);
    }

    String text() {
        return text;
    }

    @Override
    public String getElementName() {
        return ELEMENT;
    }

    @Override
    public String getNamespace() {
        return StanzaError.ERROR_CONDITION_AND_TEXT_NAMESPACE;
    }

    @Override
    public String toXML(XmlEnvironment xmlEnvironment) {
        StringBuilder sb = new StringBuilder(text.length() + 96);
        sb.append("<text xmlns='").append(StanzaError.ERROR_CONDITION_AND_TEXT_NAMESPACE).append("' xml:lang='en'>");
        SweXml.escape(text, sb);
        return sb.append("</text>").toString();
    }
}
