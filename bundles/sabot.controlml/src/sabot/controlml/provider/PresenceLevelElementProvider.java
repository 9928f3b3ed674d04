package sabot.controlml.provider;

import java.io.IOException;

import org.jivesoftware.smack.packet.XmlEnvironment;
import org.jivesoftware.smack.provider.ExtensionElementProvider;
import org.jivesoftware.smack.xml.XmlPullParser;
import org.jivesoftware.smack.xml.XmlPullParserException;

import sabot.controlml.PresenceLevel;
import sabot.controlml.PresenceLevelElement;

/**
 * Reads {@code <presence-level/>}. A presence is not a request that can be answered, so an element that is not
 * acceptable (unknown level, bad flag) yields {@link PresenceLevelElement#unreadable()}, and readers fall back to the
 * presence's {@code show}.
 */
public final class PresenceLevelElementProvider extends ExtensionElementProvider<PresenceLevelElement> {

    @Override
    public PresenceLevelElement parse(XmlPullParser parser, int initialDepth, XmlEnvironment xmlEnvironment)
            throws XmlPullParserException, IOException {
        PresenceLevel level = PresenceLevel.fromAttribute(parser.getAttributeValue("", "level"));
        String mission = parser.getAttributeValue("", "mission");
        String maintenance = parser.getAttributeValue("", "maintenance");
        ControlMlElementProvider.skipToEnd(parser, initialDepth);
        if (level == null || mission == null || mission.length() > 32 || !("true".equals(maintenance) || "false"
                .equals(maintenance))) {
            return PresenceLevelElement.unreadable();
        }
        return new PresenceLevelElement(level, mission, Boolean.parseBoolean(maintenance));
    }
}
