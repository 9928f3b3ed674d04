package sabot.fleet.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.time.Duration;
import java.time.Instant;
import java.time.temporal.ChronoUnit;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.TreeMap;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.XMPPException.XMPPErrorException;
import org.jivesoftware.smack.packet.IQ;
import org.jivesoftware.smack.packet.StanzaError;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.Tag;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;
import org.jxmpp.jid.EntityBareJid;

import com.google.gson.JsonElement;
import com.google.gson.JsonObject;
import com.google.gson.JsonParser;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Resources;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.fleet.CommandHistory;
import sabot.fleet.ServerFigures;
import sabot.fleet.ServerStatistics;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * {@code ./sabot stats} ({@code product/bin/sabot-stats}, docs/STATISTICS.md) on a private ejabberd with the archive:
 * the server's own figures from its admin API (the device's session), and per device the requests, answers, errors by
 * condition, answer times and telemetry the test's clients sent; the same over XMPP ({@link ServerStatistics}) for the
 * lab's roles only; bad arguments and requests refused with why.
 */
@Tag("ejabberd")
class ServerStatisticsTest {

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.ejabberd().sqlArchive();

    private static final String PASSWORD = "stats-pw";
    private static final long TIMEOUT_S = 10;

    @Test
    void statisticsCountWhatTheClientsSentWithErrorsByCondition() throws Exception {
        ArchiveLab lab = ArchiveLab.on(XMPP, "stats", PASSWORD);
        EntityBareJid robotJid = lab.robotJid();
        XMPPTCPConnection robot = lab.robot();
        XMPPTCPConnection operator = lab.operator();
        XMPPTCPConnection observer = lab.observer();
        XMPPTCPConnection stranger = lab.stranger();
        String before = Instant.now().minus(1, ChronoUnit.SECONDS).toString();

        // 4 goals and 2 gets from the operator; 2 goals refused to the observer, 1 to a stranger
        ControlMlManager op = ControlMlManager.getInstanceFor(operator);
        for (int i = 1; i <= 4; i++) {
            assertTrue(op.set(robot.getUser(), Resources.GOAL, new Goal(new Pose2D(i, 0, 0), 0.1, 0.1)).isSuccess());
        }
        for (int i = 0; i < 2; i++) {
            assertTrue(op.get(robot.getUser(), Resources.GOAL).isSuccess());
            assertEquals(ControlMlCondition.SET_NOT_PERMITTED, ControlMlManager.getInstanceFor(observer).set(robot
                    .getUser(), Resources.GOAL, new Goal(new Pose2D(5, 5, 0), 0.1, 0.1)).errorOrNull().cmCondition());
        }
        assertEquals(ControlMlCondition.ACCESS_DENIED, ControlMlManager.getInstanceFor(stranger).set(robot.getUser(),
                Resources.GOAL, new Goal(new Pose2D(9, 9, 0), 0.1, 0.1)).errorOrNull().cmCondition());
        // 10 telemetry values: 11 publications (ejabberd 23.01 refuses the first one's publish-options, and the
        // client sends that value again without them: docs/ARCHIVE.md)
        var telemetry = ControlMlManager.getInstanceFor(robot).telemetry();
        for (int i = 0; i < 10; i++) {
            telemetry.publishNow(Resources.POSITION, new PoseEstimate(Instant.now(), new Pose2D(i, 0, 0),
                    PoseCovariance.diagonal(0.01, 0.01, 0.01)));
        }

        List<String> lines = awaitDevice(robotJid.toString(), 9 + 9 + 11, "--since", before, "--json");
        JsonObject server = JsonParser.parseString(lines.get(0)).getAsJsonObject();
        assertEquals("ejabberd", server.get("server").getAsString());
        assertTrue(server.get("sessions").getAsInt() >= 4, lines.get(0));
        assertTrue(server.get("registered").getAsInt() >= 4, lines.get(0));
        assertEquals(robotJid.toString(), server.get("device").getAsString());
        assertEquals(1, server.getAsJsonArray("device_sessions").size(), "the robot's one session: " + lines.get(0));
        assertEquals(robot.getUser().getResourceOrThrow().toString(), server.getAsJsonArray("device_sessions").get(0)
                .getAsJsonObject().get("resource").getAsString());

        JsonObject device = JsonParser.parseString(lines.get(1)).getAsJsonObject();
        assertEquals(robotJid.toString(), device.get("device").getAsString());
        assertEquals(9, device.get("requests").getAsInt(), lines.get(1));
        assertEquals(2, device.get("gets").getAsInt());
        assertEquals(7, device.get("sets").getAsInt());
        assertEquals(9, device.get("answers").getAsInt());
        assertEquals(6, device.get("results").getAsInt());
        assertEquals(3, device.get("errors").getAsInt());
        assertEquals(Map.of("access-denied", 1, "set-not-permitted", 2), counts(device.getAsJsonObject(
                "errors_by_condition")));
        assertEquals(9, device.get("answered").getAsInt());
        double p50 = device.get("answer_p50_ms").getAsDouble();
        double p99 = device.get("answer_p99_ms").getAsDouble();
        assertTrue(p50 >= 0 && p50 <= p99 && p99 < TIMEOUT_S * 1000, lines.get(1));
        assertEquals(11, device.get("telemetry").getAsInt());
        assertTrue(device.get("telemetry_age_s").getAsDouble() >= 0, lines.get(1));
        assertEquals(29, device.get("stanzas").getAsInt());
        assertEquals(29, counts(device.getAsJsonObject("stanzas_by_node")).values().stream().mapToInt(
                Integer::intValue).sum());
        JsonObject goal = device.getAsJsonObject("resources").getAsJsonObject("cm.goal");
        assertEquals(Map.of("get", 2, "set", 7, "result", 6, "error", 3), counts(goal));
        assertEquals(Map.of("telemetry", 11), counts(device.getAsJsonObject("resources").getAsJsonObject(
                "cm.position")));

        // the same over XMPP (urn:sabot:archive:1), for an account of the lab's roles
        ServerFigures f = ServerStatistics.read(observer, robotJid, Duration.ofMinutes(5));
        assertEquals(robotJid.toString(), f.device());
        assertEquals(1, f.sessions());
        assertEquals(List.of(9L, 2L, 7L, 0L, 9L, 6L, 3L, 9L, 11L, 29L), List.of(f.requests(), f.gets(), f.sets(), f
                .stored(), f.answers(), f.results(), f.errors(), f.answered(), f.telemetry(), f.stanzas()), f.toString());
        assertEquals(Map.of("access-denied", 1L, "set-not-permitted", 2L), f.errorsByCondition());
        assertEquals(p50, f.answerP50Ms(), 0.05, f.toString());
        assertEquals(p99, f.answerP99Ms(), 0.05, f.toString());
        assertEquals(29L, f.stanzasByNode().values().stream().mapToLong(Long::longValue).sum());
        assertTrue(f.telemetryAgeS() >= 0 && f.telemetryAgeS() < 60, f.toString());
        XMPPErrorException forbidden = assertThrows(XMPPErrorException.class, () -> ServerStatistics.read(stranger,
                robotJid, Duration.ofMinutes(5)));
        assertEquals(StanzaError.Condition.forbidden, forbidden.getStanzaError().getCondition());
        Map<Map<String, String>, String> badRequests = Map.of(
                Map.of("device", "not a jid@@"), "device: expected a bare JID",
                Map.of("device", robotJid.toString(), "seconds", "0"), "seconds: expected 1..604800",
                Map.of("device", robotJid.toString(), "seconds", "604801"), "seconds: expected 1..604800",
                Map.of("device", robotJid.toString(), "seconds", "x"), "seconds: expected 1..604800");
        List<String> unexpectedAnswers = new ArrayList<>();
        for (var request : badRequests.entrySet()) {
            XMPPErrorException e = assertThrows(XMPPErrorException.class, () -> operator
                    .sendIqRequestAndWaitForResponse(statisticsIq(request.getKey())));
            if (e.getStanzaError().getCondition() != StanzaError.Condition.bad_request || !e.getStanzaError()
                    .getDescriptiveText().contains(request.getValue())) {
                unexpectedAnswers.add(request.getKey() + ": " + e.getStanzaError());
            }
        }
        assertEquals(List.of(), unexpectedAnswers);

        // the text form: the server's figures, then the device's line with its errors by condition
        List<String> text = XMPP.statistics(robotJid.getLocalpart().toString(), "--since", before);
        String all = String.join("\n", text);
        System.out.println("[figure] ./sabot stats " + robotJid.getLocalpart() + " --since " + before + ":\n" + all);
        assertTrue(text.get(0).startsWith("server: ejabberd, up "), all);
        assertTrue(all.contains("  " + robotJid + ": 9 requests (2 get, 7 set); 9 answers (6 result, 3 error: "
                + "access-denied 1, set-not-permitted 2); answer p50 "), all);
        assertTrue(all.contains("11 telemetry ("), all);
        assertTrue(all.contains("    cm.goal: 2 get, 7 set, 6 result, 3 error"), all);
        // nothing before the test sent it
        JsonObject empty = JsonParser.parseString(XMPP.statistics(robotJid.toString(), "--until", before,
                "--since", "1h", "--json").get(1)).getAsJsonObject();
        assertEquals(0, empty.get("stanzas").getAsInt());
    }

    @Test
    void badArgumentsToStatisticsAreRefusedWithWhy() {
        Map<List<String>, String> bad = Map.of(
                List.of("--since", "yesterday"), "expected an ISO 8601 time",
                List.of("--until", "5y"), "expected an ISO 8601 time",
                List.of("x'; DROP TABLE sabot_archive; --"), "expected a bare JID",
                List.of("--what"), "unknown option '--what'",
                List.of("a@sabot.local", "b@sabot.local"), "one JID at most",
                List.of("--since"), "--since needs a value",
                List.of("--since", "1m", "--until", "2h"), "--until is not after --since");
        List<String> unexpected = new ArrayList<>();
        bad.forEach((args, why) -> {
            IOException e = assertThrows(IOException.class, () -> XMPP.statistics(args.toArray(String[]::new)),
                    String.valueOf(args));
            if (!e.getMessage().contains(why)) {
                unexpected.add(args + ": " + e.getMessage());
            }
        });
        assertEquals(List.of(), unexpected);
    }

    /** A statistics request with any attributes, as a client that does not use {@link ServerStatistics} may send. */
    private static IQ statisticsIq(Map<String, String> attributes) {
        IQ iq = new IQ(ServerStatistics.ELEMENT, CommandHistory.NAMESPACE) {
            @Override
            protected IQChildElementXmlStringBuilder getIQChildElementBuilder(IQChildElementXmlStringBuilder xml) {
                attributes.forEach(xml::attribute);
                xml.setEmptyElement();
                return xml;
            }
        };
        iq.setType(IQ.Type.get);
        iq.setTo(PrivateXmppServer.domainJid(PrivateXmppServer.DOMAIN));
        return iq;
    }

    private static Map<String, Integer> counts(JsonObject o) {
        Map<String, Integer> m = new TreeMap<>();
        for (Map.Entry<String, JsonElement> e : o.entrySet()) {
            m.put(e.getKey(), e.getValue().getAsInt());
        }
        return m;
    }

    /**
     * Polls the statistics until the device's archived stanzas reach {@code stanzas}: the server writes its rows every
     * 200 ms, in a database that is another process (there is no event to wait on).
     */
    private static List<String> awaitDevice(String device, int stanzas, String... arguments) throws Exception {
        List<String> args = new ArrayList<>(List.of(device));
        args.addAll(List.of(arguments));
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);
        while (true) {
            List<String> got = XMPP.statistics(args.toArray(String[]::new));
            int n = JsonParser.parseString(got.get(1)).getAsJsonObject().get("stanzas").getAsInt();
            if (n >= stanzas || System.nanoTime() > deadline) {
                return got;
            }
            Thread.sleep(100);
        }
    }
}
