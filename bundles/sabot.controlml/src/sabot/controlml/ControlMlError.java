package sabot.controlml;

import java.util.Objects;

import org.jivesoftware.smack.packet.StandardExtensionElement;
import org.jivesoftware.smack.packet.StanzaError;

/**
 * Why a ControlML request failed: an RFC 6120 condition, ControlML's own condition and a human-readable text.
 *
 * @param condition   the RFC 6120 stanza error condition; never null
 * @param cmCondition the ControlML condition; never null ({@link ControlMlCondition#UNSPECIFIED} when the answer
 *                    carried none)
 * @param text        an English explanation for an operator; never null, may be empty
 */
public record ControlMlError(StanzaError.Condition condition, ControlMlCondition cmCondition, String text) {

    public ControlMlError {
        Objects.requireNonNull(condition, "condition");
        Objects.requireNonNull(cmCondition, "cmCondition");
        text = text == null ? "" : text;
    }

    /** @return an error reported under the condition's usual RFC 6120 condition */
    public static ControlMlError of(ControlMlCondition cmCondition, String text) {
        return new ControlMlError(cmCondition.stanzaCondition(), cmCondition, text);
    }

    /**
     * @return the error as a Smack stanza error: the RFC 6120 condition, the text as
     *         {@code <text xmlns='urn:ietf:params:xml:ns:xmpp-stanzas' xml:lang='en'>} and the ControlML condition
     *         element. The text is an extension written literally, not {@code setDescriptiveEnText}: Smack 4.4.8's
     *         connection writer drops the text's namespace (see {@link DescriptiveText}).
     */
    public StanzaError toStanzaError() {
        StanzaError.Builder b = StanzaError.getBuilder(condition);
        if (!text.isEmpty()) {
            b.addExtension(new DescriptiveText(text));
        }
        if (cmCondition != ControlMlCondition.UNSPECIFIED) {
            b.addExtension(new ConditionElement(cmCondition));
        }
        return b.build();
    }

    /** @return the error carried by a Smack stanza error */
    public static ControlMlError fromStanzaError(StanzaError error) {
        ControlMlCondition cm = ControlMlCondition.UNSPECIFIED;
        for (ControlMlCondition c : ControlMlCondition.values()) {
            if (error.getExtension(c.element(), ControlMl.ERRORS_NAMESPACE) != null) {
                cm = c;
                break;
            }
        }
        String text = error.getDescriptiveText("en");
        if (text == null) {
            text = error.getDescriptiveText();
        }
        if (text == null && error.getExtension(DescriptiveText.ELEMENT,
                StanzaError.ERROR_CONDITION_AND_TEXT_NAMESPACE) instanceof DescriptiveText own) {
            text = own.text(); // built locally, not parsed
        }
        if (text == null && error.getExtension(DescriptiveText.ELEMENT, "jabber:client")
                instanceof StandardExtensionElement unqualified) {
            text = unqualified.getText(); // a peer whose Smack 4.4 writer dropped the text's namespace
        }
        return new ControlMlError(error.getCondition(), cm, text == null ? error.getConditionText() : text);
    }

    @Override
    public String toString() {
        return condition + "/" + cmCondition.element() + (text.isEmpty() ? "" : ": " + text);
    }
}
