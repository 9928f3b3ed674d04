package sabot.controlml;

import java.util.Objects;

import org.jivesoftware.smack.packet.IQ;
import org.jivesoftware.smack.packet.IqData;

import sabot.controlml.swe.IsoInstant;

/**
 * An {@code <iq/>} carrying one {@code <control-ml/>}: requests ({@code iq get/set} with control-ml get/set) and
 * their answers ({@code iq result} with control-ml result; {@code iq error} with control-ml error plus the RFC 6120
 * {@code <error/>} whose application condition is a {@link ConditionElement}).
 */
public final class ControlMlIQ extends IQ {

    private final ControlMlElement element;

    /** A request or answer to send; the IQ type follows the element's type. */
    public ControlMlIQ(ControlMlElement element) {
        super(ControlMl.ELEMENT, ControlMl.NAMESPACE);
        this.element = Objects.requireNonNull(element);
        setType(iqTypeFor(element.type()));
        if (element.type() == ControlMlType.ERROR) {
            setError(element.failure().toStanzaError());
        }
    }

    /** As received: the IQ's attributes come from {@code iqData} (the provider's view). */
    public ControlMlIQ(IqData iqData, ControlMlElement element) {
        super(iqData, ControlMl.ELEMENT, ControlMl.NAMESPACE);
        this.element = Objects.requireNonNull(element);
    }

    /** @return the IQ type that carries a control-ml type */
    public static IQ.Type iqTypeFor(ControlMlType type) {
        if (type == null) {
            return IQ.Type.error;
        }
        return switch (type) {
            case GET -> IQ.Type.get;
            case SET -> IQ.Type.set;
            case RESULT -> IQ.Type.result;
            case ERROR -> IQ.Type.error;
        };
    }

    /** @return the carried element */
    public ControlMlElement element() {
        return element;
    }

    @Override
    protected IQChildElementXmlStringBuilder getIQChildElementBuilder(IQChildElementXmlStringBuilder xml) {
        if (element.type() != null) {
            xml.attribute("type", element.type().attribute());
        }
        if (element.id() != null) {
            xml.attribute("id", element.id().toString());
        }
        if (element.res() != null) {
            xml.attribute("res", element.res());
        }
        if (element.sent() != null) {
            StringBuilder sent = new StringBuilder(30);
            IsoInstant.format(element.sent(), sent);
            xml.attribute("sent", sent);
        }
        String content = element.contentXml();
        if (content.isEmpty()) {
            xml.setEmptyElement();
        } else {
            xml.rightAngleBracket();
            xml.append(content);
        }
        return xml;
    }
}
