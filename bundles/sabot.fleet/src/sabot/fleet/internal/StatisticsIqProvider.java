package sabot.fleet.internal;

import java.io.IOException;
import java.time.Duration;
import java.util.Map;
import java.util.TreeMap;

import org.jivesoftware.smack.packet.IqData;
import org.jivesoftware.smack.packet.XmlEnvironment;
import org.jivesoftware.smack.provider.IqProvider;
import org.jivesoftware.smack.xml.XmlPullParser;
import org.jivesoftware.smack.xml.XmlPullParserException;

import sabot.fleet.ServerFigures;

/**
 * Reads the server's answer {@code <statistics device='..' seconds='..' requests='..' ...><error condition count/>
 * <node name count/></statistics>}, and the request a server echoes in an error. Never throws for a malformed answer
 * (Smack would close the connection): it is kept as the IQ's {@link StatisticsIq#problem() problem}.
 */
public final class StatisticsIqProvider extends IqProvider<StatisticsIq> {

    @Override
    public StatisticsIq parse(XmlPullParser parser, int initialDepth, IqData iqData, XmlEnvironment xmlEnvironment)
            throws XmlPullParserException, IOException {
        Map<String, String> attributes = new TreeMap<>();
        for (int i = 0; i < parser.getAttributeCount(); i++) {
            attributes.put(parser.getAttributeName(i), parser.getAttributeValue(i));
        }
        Map<String, Long> errors = new TreeMap<>();
        Map<String, Long> nodes = new TreeMap<>();
        String problem = null;
        while (true) {
            XmlPullParser.Event event = parser.next();
            if (event == XmlPullParser.Event.START_ELEMENT) {
                try {
                    if ("error".equals(parser.getName())) {
                        errors.put(attribute(parser, "condition"), Long.parseLong(attribute(parser, "count")));
                    } else if ("node".equals(parser.getName())) {
                        nodes.put(attribute(parser, "name"), Long.parseLong(attribute(parser, "count")));
                    }
                } catch (RuntimeException e) {
                    problem = parser.getName() + ": " + e.getMessage();
                }
            } else if (event == XmlPullParser.Event.END_ELEMENT && parser.getDepth() == initialDepth) {
                break;
            }
        }
        if (!attributes.containsKey("seconds") || !attributes.containsKey("requests")) {
            return StatisticsIq.answer(null, problem); // a request (echoed in an error), not an answer
        }
        try {
            ServerFigures f = new ServerFigures(attributes.get("device"), Duration.ofSeconds(Long.parseLong(attributes.get(
                    "seconds"))), (int) count(attributes, "sessions"), count(attributes, "requests"), count(attributes,
                            "gets"), count(attributes, "sets"), count(attributes, "stored"), count(attributes,
                                    "answers"), count(attributes, "results"), count(attributes, "errors"), errors,
                    count(attributes, "answered"), decimal(attributes, "p50"), decimal(attributes, "p99"), count(
                            attributes, "telemetry"), decimal(attributes, "age"), count(attributes, "stanzas"), nodes);
            return StatisticsIq.answer(problem == null ? f : null, problem);
        } catch (RuntimeException e) {
            return StatisticsIq.answer(null, String.valueOf(e.getMessage()));
        }
    }

    private static long count(Map<String, String> attributes, String name) {
        String v = attributes.get(name);
        return v == null ? 0 : Long.parseLong(v);
    }

    /** @return the attribute's number, NaN when absent (no such figure in the window) */
    private static double decimal(Map<String, String> attributes, String name) {
        String v = attributes.get(name);
        return v == null ? Double.NaN : Double.parseDouble(v);
    }

    private static String attribute(XmlPullParser p, String name) {
        String v = p.getAttributeValue("", name);
        return v == null ? "" : v;
    }
}
