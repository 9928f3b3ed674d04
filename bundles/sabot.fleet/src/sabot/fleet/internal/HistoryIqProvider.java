package sabot.fleet.internal;

import java.io.IOException;
import java.math.BigDecimal;
import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.List;

import org.jivesoftware.smack.packet.IqData;
import org.jivesoftware.smack.packet.XmlEnvironment;
import org.jivesoftware.smack.provider.IqProvider;
import org.jivesoftware.smack.xml.XmlPullParser;
import org.jivesoftware.smack.xml.XmlPullParserException;

import sabot.fleet.ArchivedCommand;

/**
 * Reads the server's answer {@code <history device='...'><command seq='..' at='..' .../>...</history>}, and the
 * request a server echoes in an error. Never throws for a malformed command (Smack would close the connection): it
 * is kept as a {@link HistoryIq#problems() problem}.
 */
public final class HistoryIqProvider extends IqProvider<HistoryIq> {

    @Override
    public HistoryIq parse(XmlPullParser parser, int initialDepth, IqData iqData, XmlEnvironment xmlEnvironment)
            throws XmlPullParserException, IOException {
        List<ArchivedCommand> commands = new ArrayList<>();
        List<String> problems = new ArrayList<>();
        while (true) {
            XmlPullParser.Event event = parser.next();
            if (event == XmlPullParser.Event.START_ELEMENT && "command".equals(parser.getName())) {
                try {
                    commands.add(command(parser));
                } catch (RuntimeException e) {
                    problems.add("command " + attribute(parser, "seq") + ": " + e.getMessage());
                }
            } else if (event == XmlPullParser.Event.END_ELEMENT && parser.getDepth() == initialDepth) {
                break;
            }
        }
        return HistoryIq.answer(commands, problems);
    }

    private static ArchivedCommand command(XmlPullParser p) {
        String ms = attribute(p, "ms");
        return new ArchivedCommand(Long.parseLong(attribute(p, "seq")), Instant.parse(attribute(p, "at")), "message".equals(
                attribute(p, "via")), attribute(p, "res"), attribute(p, "id"), attribute(p, "from"), attribute(p,
                        "answer"), attribute(p, "condition"), attribute(p, "text"), ms.isEmpty() ? null : Duration
                                .ofNanos(new BigDecimal(ms).movePointRight(6).longValue()));
    }

    private static String attribute(XmlPullParser p, String name) {
        String v = p.getAttributeValue("", name);
        return v == null ? "" : v;
    }
}
