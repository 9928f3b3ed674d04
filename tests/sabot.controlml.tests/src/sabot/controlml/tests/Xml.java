package sabot.controlml.tests;

import org.jivesoftware.smack.packet.Stanza;
import org.jivesoftware.smack.packet.XmlEnvironment;
import org.jivesoftware.smack.util.PacketParserUtils;
import org.jivesoftware.smack.xml.SmackXmlParser;
import org.jivesoftware.smack.xml.XmlPullParser;

import sabot.controlml.ControlMlElement;
import sabot.controlml.provider.ControlMlElementProvider;
import sabot.controlml.provider.ControlMlProviders;

/** Parsing helpers: what Smack does with a stanza from the wire, without a connection. */
final class Xml {

    static {
        ControlMlProviders.register();
        // Smack looks the parser factory up through the ServiceLoader on every new parser unless one is set; the
        // fuzzer creates 100,000 parsers.
        SmackXmlParser.setXmlPullParserFactory(SmackXmlParser.getXmlPullParserFactory());
    }

    private Xml() {
    }

    /** Parses a {@code <control-ml/>} element the way the provider sees it inside a stanza. */
    static ControlMlElement element(String xml) throws Exception {
        XmlPullParser parser = PacketParserUtils.getParserFor(xml);
        int depth = parser.getDepth();
        ControlMlElement e = ControlMlElementProvider.parseElement(parser, depth);
        if (parser.getEventType() != XmlPullParser.Event.END_ELEMENT || parser.getDepth() != depth) {
            throw new AssertionError("provider did not stop on control-ml's end tag");
        }
        return e;
    }

    /** Parses a whole stanza with Smack's parser (providers looked up as on a connection). */
    static Stanza stanza(String xml) throws Exception {
        return PacketParserUtils.parseStanza(xml);
    }

    static String xml(org.jivesoftware.smack.packet.Element e) {
        return e.toXML(XmlEnvironment.EMPTY).toString();
    }
}
