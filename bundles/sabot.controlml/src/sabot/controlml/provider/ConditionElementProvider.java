package sabot.controlml.provider;

import java.io.IOException;

import org.jivesoftware.smack.packet.XmlEnvironment;
import org.jivesoftware.smack.provider.ExtensionElementProvider;
import org.jivesoftware.smack.xml.XmlPullParser;
import org.jivesoftware.smack.xml.XmlPullParserException;

import sabot.controlml.ConditionElement;
import sabot.controlml.ControlMlCondition;

/** Reads the ControlML condition elements inside a stanza {@code <error/>}. */
public final class ConditionElementProvider extends ExtensionElementProvider<ConditionElement> {

    @Override
    public ConditionElement parse(XmlPullParser parser, int initialDepth, XmlEnvironment xmlEnvironment)
            throws XmlPullParserException, IOException {
        ControlMlCondition condition = ControlMlCondition.fromElement(parser.getName());
        ControlMlElementProvider.skipToEnd(parser, initialDepth);
        return new ConditionElement(condition == null ? ControlMlCondition.UNSPECIFIED : condition);
    }
}
