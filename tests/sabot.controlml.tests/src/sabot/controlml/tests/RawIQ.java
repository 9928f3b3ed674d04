package sabot.controlml.tests;

import org.jivesoftware.smack.packet.IQ;

import sabot.controlml.ControlMl;

/** An IQ whose control-ml attributes and content are written verbatim: how a buggy or hostile client would send. */
final class RawIQ extends IQ {

    private final String attributes;
    private final String content;

    RawIQ(IQ.Type type, String attributes, String content) {
        super(ControlMl.ELEMENT, ControlMl.NAMESPACE);
        setType(type);
        this.attributes = attributes;
        this.content = content;
    }

    @Override
    protected IQChildElementXmlStringBuilder getIQChildElementBuilder(IQChildElementXmlStringBuilder xml) {
        xml.append(" ").append(attributes);
        if (content.isEmpty()) {
            xml.setEmptyElement();
        } else {
            xml.rightAngleBracket();
            xml.append(content);
        }
        return xml;
    }
}
