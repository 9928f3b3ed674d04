package sabot.controlml;

import java.util.Objects;

import org.jivesoftware.smack.packet.ExtensionElement;
import org.jivesoftware.smack.packet.XmlEnvironment;

/**
 * The application-specific condition element inside a stanza {@code <error/>}, e.g.
 * {@code <stale-command xmlns='urn:sabot:controlml:1:errors'/>}.
 */
public final class ConditionElement implements ExtensionElement {

    private final ControlMlCondition condition;

    public ConditionElement(ControlMlCondition condition) {
        this.condition = Objects.requireNonNull(condition);
    }

    /** @return the condition */
    public ControlMlCondition condition() {
        return condition;
    }

    @Override
    public String getElementName() {
        return condition.element();
    }

    @Override
    public String getNamespace() {
        return ControlMl.ERRORS_NAMESPACE;
    }

    @Override
    public CharSequence toXML(XmlEnvironment xmlEnvironment) {
        return "<" + condition.element() + " xmlns='" + ControlMl.ERRORS_NAMESPACE + "'/>";
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof ConditionElement c && c.condition == condition;
    }

    @Override
    public int hashCode() {
        return condition.hashCode();
    }
}
