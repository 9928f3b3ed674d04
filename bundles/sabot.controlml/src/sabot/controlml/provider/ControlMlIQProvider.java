package sabot.controlml.provider;

import java.io.IOException;

import org.jivesoftware.smack.packet.IqData;
import org.jivesoftware.smack.packet.XmlEnvironment;
import org.jivesoftware.smack.provider.IqProvider;
import org.jivesoftware.smack.xml.XmlPullParser;
import org.jivesoftware.smack.xml.XmlPullParserException;

import sabot.controlml.ControlMlIQ;

/** Reads an {@code <iq/>}'s {@code <control-ml/>} child; as strict and total as {@link ControlMlElementProvider}. */
public final class ControlMlIQProvider extends IqProvider<ControlMlIQ> {

    @Override
    public ControlMlIQ parse(XmlPullParser parser, int initialDepth, IqData iqData, XmlEnvironment xmlEnvironment)
            throws XmlPullParserException, IOException {
        return new ControlMlIQ(iqData, ControlMlElementProvider.parseElement(parser, initialDepth));
    }
}
