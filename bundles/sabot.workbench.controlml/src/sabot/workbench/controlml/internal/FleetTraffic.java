package sabot.workbench.controlml.internal;

import java.util.Map;
import java.util.Optional;
import java.util.concurrent.ConcurrentHashMap;
import java.util.function.LongSupplier;
import java.util.function.Predicate;

import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.packet.Stanza;
import org.jivesoftware.smack.packet.XmlEnvironment;
import org.jivesoftware.smack.util.XmlStringBuilder;
import org.jxmpp.jid.Jid;

import sabot.controlml.ControlMlCondition;
import sabot.workbench.fleet.TrafficStatistics;

/**
 * The workbench's own count of its traffic with each followed robot ({@link TrafficStatistics}): every stanza in and
 * out of the session's connection whose peer is a followed robot, the requests of {@link FleetRequests} with their
 * round trips and errors, the telemetry items of {@link FleetTelemetry}. Counting starts again with each session.
 */
final class FleetTraffic {

    private final LongSupplier nanos;
    private final Predicate<String> followed;
    private final Map<String, RobotTraffic> robots = new ConcurrentHashMap<>();
    private volatile boolean counting;

    /**
     * @param nanos    the monotonic clock ({@code System::nanoTime})
     * @param followed whether a bare JID is a robot of the fleet
     */
    FleetTraffic(LongSupplier nanos, Predicate<String> followed) {
        this.nanos = nanos;
        this.followed = followed;
    }

    /** Connection thread, before login: counts the new session's stanzas from zero. */
    void listen(XMPPConnection connection) {
        robots.clear();
        counting = true;
        // Smack's processing thread, in order; the sending listener runs on the thread that sends
        connection.addStanzaListener(stanza -> count(stanza.getFrom(), stanza, true), stanza -> stanza
                .getFrom() != null);
        connection.addStanzaSendingListener(stanza -> count(stanza.getTo(), stanza, false), stanza -> stanza
                .getTo() != null);
    }

    private void count(Jid peer, Stanza stanza, boolean in) {
        RobotTraffic t = of(peer.asBareJid().toString());
        if (t != null) {
            long bytes = utf8Length(stanza.toXML());
            if (in) {
                t.received(nanos.getAsLong(), bytes);
            } else {
                t.sent(nanos.getAsLong(), bytes);
            }
        }
    }

    /** A telemetry item from {@code robot}. */
    void telemetry(String robot) {
        RobotTraffic t = of(robot);
        if (t != null) {
            t.telemetry(nanos.getAsLong());
        }
    }

    /**
     * A request is being sent to {@code robot}.
     *
     * @return when, for {@link #answered}
     */
    long requesting(String robot) {
        RobotTraffic t = of(robot);
        if (t != null) {
            t.requested();
        }
        return nanos.getAsLong();
    }

    /**
     * The request sent to {@code robot} at {@code sentNanos} ({@link #requesting}) was answered now.
     *
     * @param error its condition, null for a result
     */
    void answered(String robot, long sentNanos, ControlMlCondition error) {
        RobotTraffic t = of(robot);
        if (t != null) {
            long now = nanos.getAsLong();
            t.answered(now, now - sentNanos, error);
        }
    }

    /** @return the counters of a followed robot, empty before the first session or for another JID */
    Optional<TrafficStatistics> snapshot(String robot) {
        RobotTraffic t = of(robot);
        return t == null ? Optional.empty() : Optional.of(t.snapshot(nanos.getAsLong()));
    }

    private RobotTraffic of(String robot) {
        if (!counting || !followed.test(robot)) {
            return null;
        }
        return robots.computeIfAbsent(robot, r -> new RobotTraffic(r, nanos.getAsLong()));
    }

    /** @return the UTF-8 length of a stanza's XML, without encoding it */
    static long utf8Length(CharSequence xml) {
        // Smack's XmlStringBuilder is a tree of LazyStringBuilders whose length() and charAt(i) walk their parts, and
        // whose toString() appends nested builders char by char: time quadratic in the stanza's size (with five
        // robots' telemetry, some 80 % of the workbench's CPU went here). Its flat list of parts is what Smack's own
        // writer sends: count those.
        if (xml instanceof XmlStringBuilder tree) {
            long n = 0;
            for (CharSequence part : tree.toList(XmlEnvironment.EMPTY)) {
                n += utf8Length(part.toString());
            }
            return n;
        }
        String text = xml.toString();
        long n = 0;
        for (int i = 0; i < text.length(); i++) {
            char c = text.charAt(i);
            if (c < 0x80) {
                n++;
            } else if (c < 0x800) {
                n += 2;
            } else if (Character.isHighSurrogate(c) && i + 1 < text.length()) {
                n += 4; // a supplementary character: two chars, four bytes
                i++;
            } else {
                n += 3;
            }
        }
        return n;
    }
}
