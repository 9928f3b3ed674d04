package sabot.fleet.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.time.Instant;
import java.time.temporal.ChronoUnit;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.TreeMap;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

import org.jivesoftware.smack.XMPPException.XMPPErrorException;
import org.jivesoftware.smack.packet.IQ;
import org.jivesoftware.smack.packet.StanzaError;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.Tag;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;
import org.jxmpp.jid.EntityBareJid;

import sabot.controlml.AccessPolicy;
import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.fleet.AccessRules;
import sabot.fleet.ArchivedCommand;
import sabot.fleet.CommandHistory;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * The archive of every ControlML stanza (docs/ARCHIVE.md) on a private ejabberd with its private PostgreSQL
 * ({@code sabot-xmpp start --archive sql}): requests, answers, a command stored for the device and telemetry are
 * rows of the database, read back with {@code sabot-log} (what {@code ./sabot log} runs) and as a device's command
 * history over XMPP ({@link CommandHistory}), each command with who sent it and its answer; bad arguments to either
 * are refused with why.
 */
@Tag("ejabberd")
class ArchiveTest {

    static final long TIMEOUT_S = 10;

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.ejabberd().sqlArchive();

    private static final String PASSWORD = "archive-pw";

    @Test
    void everyControlMlStanzaIsArchivedAndTheLogShowsEachCommandWithItsSenderAndAnswer() throws Exception {
        EntityBareJid robotJid = XMPP.register("arch-robot", PrivateXmppServer.DOMAIN, PASSWORD);
        EntityBareJid operatorJid = XMPP.register("arch-operator", PrivateXmppServer.DOMAIN, PASSWORD);
        XMPP.register("arch-stranger", PrivateXmppServer.DOMAIN, PASSWORD);
        XMPPTCPConnection robot = login("arch-robot");
        XMPPTCPConnection operator = login("arch-operator");
        XMPPTCPConnection stranger = login("arch-stranger");
        AccessPolicy policy = AccessRules.labGroups().on(robot);
        Goal[] goal = FleetOnServerTest.goalDevice(robot, policy);
        XMPP.enrolRobot(robotJid);
        XMPP.grant(operatorJid, Role.OPERATOR);
        FleetOnServerTest.awaitRole(Roster.getInstanceFor(robot), policy, operator, Role.OPERATOR);
        String before = Instant.now().minus(1, ChronoUnit.SECONDS).toString();

        // 3 goals and a get from the operator, a goal refused to a stranger, a goal stored for the device
        ControlMlManager op = ControlMlManager.getInstanceFor(operator);
        for (int i = 1; i <= 3; i++) {
            assertTrue(op.set(robot.getUser(), Resources.GOAL, new Goal(new Pose2D(i, 0, 0), 0.1, 0.1)).isSuccess());
        }
        assertTrue(op.get(robot.getUser(), Resources.GOAL).isSuccess());
        var refused = ControlMlManager.getInstanceFor(stranger).set(robot.getUser(), Resources.GOAL, new Goal(new Pose2D(9,
                9, 0), 0.1, 0.1)).errorOrNull();
        assertEquals(ControlMlCondition.ACCESS_DENIED, refused.cmCondition(), String.valueOf(refused));
        Goal stored = new Goal(new Pose2D(4, 0, 0), 0.1, 0.1);
        var pending = op.sendCommandMessage(robotJid, Resources.GOAL, stored);
        assertTrue(pending.outcome().get(TIMEOUT_S, TimeUnit.SECONDS).isSuccess());
        assertEquals(stored, goal[0]);
        // and 20 telemetry publications
        var telemetry = ControlMlManager.getInstanceFor(robot).telemetry();
        for (int i = 0; i < 20; i++) {
            telemetry.publishNow(Resources.POSITION, new PoseEstimate(Instant.now(), new Pose2D(i, 0, 0),
                    PoseCovariance.diagonal(0.01, 0.01, 0.01)));
        }

        // every stanza the clients sent: 6 requests, 6 answers, 21 publications of 20 values (ejabberd 23.01 refuses
        // the first publication's publish-options: the client sends that value again without them)
        List<String> all = awaitRows(33, robotJid.toString(), "--all", "--json");
        Map<String, Integer> kinds = new TreeMap<>();
        for (String row : all) {
            kinds.merge(field(row, "kind") + "/" + field(row, "via"), 1, Integer::sum);
        }
        assertEquals(Map.of("error/iq", 1, "get/iq", 1, "result/iq", 4, "set/iq", 4, "set/message", 1,
                "result/message", 1, "telemetry/pep", 21), kinds, String.join("\n", all));
        assertEquals(20, all.stream().filter(r -> field(r, "kind").equals("telemetry")).map(r -> field(r, "cm_id"))
                .distinct().count(), "telemetry values archived");

        // the commands: who sent each, and its answer
        List<String> commands = XMPP.archiveLog(robotJid.getLocalpart().toString(), "--json", "--since", before);
        assertEquals(5, commands.size(), String.join("\n", commands));
        for (int i = 0; i < 3; i++) {
            assertTrue(field(commands.get(i), "from").startsWith(operatorJid + "/"), commands.get(i));
            assertEquals("result", field(commands.get(i), "answer"), commands.get(i));
            assertEquals("cm.goal", field(commands.get(i), "res"), commands.get(i));
            assertTrue(field(commands.get(i), "xml").startsWith("<control-ml "), commands.get(i));
        }
        assertEquals(3, commands.subList(0, 3).stream().map(c -> field(c, "xml")).distinct().count(),
                "three different goals archived as the same XML");
        assertTrue(field(commands.get(3), "from").startsWith("arch-stranger@"), commands.get(3));
        assertEquals("error", field(commands.get(3), "answer"));
        assertEquals("access-denied", field(commands.get(3), "condition"), commands.get(3));
        assertEquals("message", field(commands.get(4), "via"));
        assertEquals("result", field(commands.get(4), "answer"), commands.get(4));
        assertTrue(Double.parseDouble(field(commands.get(1), "answer_ms")) >= 0, commands.get(1));

        // the text form, the requests, and the time range
        List<String> text = XMPP.archiveLog(robotJid.toString(), "--since", before);
        assertTrue(text.get(3).matches("\\S+Z arch-robot@sabot\\.local set cm\\.goal \\S+ from arch-stranger@"
                + "sabot\\.local/\\S+ -> error in [0-9.]+ ms access-denied .+"), text.get(3));
        assertEquals(6, XMPP.archiveLog(robotJid.toString(), "--requests", "--since", before).size());
        assertEquals(List.of(), XMPP.archiveLog(robotJid.toString(), "--until", before));
        assertEquals(List.of(), XMPP.archiveLog("nobody@sabot.local", "--all"));
        assertEquals(2, XMPP.archiveLog(robotJid.toString(), "--limit", "2").size());
        assertFalse(XMPP.archiveLog("--all", "--since", "1h").isEmpty(), "no row in the last hour of every device");
    }

    @Test
    void badArgumentsToTheLogAreRefusedWithWhyAndChangeNothing() throws Exception {
        // what the archive held 2 s ago (written by now: rows are written every 200 ms)
        String then = Instant.now().minus(2, ChronoUnit.SECONDS).toString();
        int rows = XMPP.archiveLog("--all", "--until", then, "--limit", "9999999").size();
        Map<List<String>, String> bad = Map.of(
                List.of("--since", "yesterday"), "expected an ISO 8601 time",
                List.of("--since", "5y"), "expected an ISO 8601 time",
                List.of("--limit", "0"), "expected 1..9999999 rows",
                List.of("x'; DROP TABLE sabot_archive; --"), "expected a bare JID",
                List.of("--all", "--what"), "unknown option '--what'",
                List.of("a@sabot.local", "b@sabot.local"), "one JID at most",
                List.of("--since"), "--since needs a value");
        List<String> unexpected = new ArrayList<>();
        bad.forEach((args, why) -> {
            IOException e = assertThrows(IOException.class, () -> XMPP.archiveLog(args.toArray(String[]::new)),
                    String.valueOf(args));
            if (!e.getMessage().contains(why)) {
                unexpected.add(args + ": " + e.getMessage());
            }
        });
        assertEquals(List.of(), unexpected);
        assertEquals(rows, XMPP.archiveLog("--all", "--until", then, "--limit", "9999999").size(),
                "a refused call changed the archive");
    }

    @Test
    void theCommandHistoryIsForTheLabsRolesNewestFirstWithEachAnswer() throws Exception {
        ArchiveLab lab = ArchiveLab.on(XMPP, "hist", PASSWORD);
        EntityBareJid robotJid = lab.robotJid();
        EntityBareJid operatorJid = lab.operatorJid();
        EntityBareJid observerJid = lab.observerJid();
        XMPPTCPConnection robot = lab.robot();
        XMPPTCPConnection operator = lab.operator();
        XMPPTCPConnection observer = lab.observer();
        XMPPTCPConnection stranger = lab.stranger();
        ControlMlManager op = ControlMlManager.getInstanceFor(operator);
        for (int i = 1; i <= 3; i++) {
            assertTrue(op.set(robot.getUser(), Resources.GOAL, new Goal(new Pose2D(i, 0, 0), 0.1, 0.1)).isSuccess());
        }
        var refused = ControlMlManager.getInstanceFor(observer).set(robot.getUser(), Resources.GOAL, new Goal(
                new Pose2D(5, 5, 0), 0.1, 0.1)).errorOrNull();
        assertEquals(ControlMlCondition.SET_NOT_PERMITTED, refused.cmCondition(), String.valueOf(refused));

        // at once: the server writes what it holds before it answers
        List<ArchivedCommand> latest = CommandHistory.read(observer, robotJid, 3);
        assertEquals(3, latest.size(), String.valueOf(latest));
        assertTrue(!latest.get(0).at().isBefore(latest.get(1).at()) && !latest.get(1).at().isBefore(latest.get(2)
                .at()), "not newest first: " + latest);
        ArchivedCommand denied = latest.get(0);
        assertTrue(denied.from().startsWith(observerJid + "/"), denied.toString());
        assertEquals("error", denied.answer());
        assertEquals("set-not-permitted", denied.condition());
        assertFalse(denied.text().isEmpty(), denied.toString());
        for (ArchivedCommand c : latest.subList(1, 3)) {
            assertTrue(c.from().startsWith(operatorJid + "/"), c.toString());
            assertEquals("cm.goal", c.resource());
            assertEquals("result", c.answer());
            assertFalse(c.stored());
            assertTrue(c.answerIn() != null && !c.answerIn().isNegative(), c.toString());
        }
        assertEquals(4, CommandHistory.read(operator, robotJid, CommandHistory.MAX).size());
        // the next page: the one command taken before the three
        List<ArchivedCommand> older = CommandHistory.readBefore(operator, robotJid, 3, latest.get(2).seq());
        assertEquals(1, older.size(), String.valueOf(older));
        assertTrue(older.get(0).at().compareTo(latest.get(2).at()) <= 0, older + " after " + latest.get(2));

        // nobody outside the lab's roles; bad requests refused with why
        XMPPErrorException forbidden = assertThrows(XMPPErrorException.class, () -> CommandHistory.read(stranger,
                robotJid, 10));
        assertEquals(StanzaError.Condition.forbidden, forbidden.getStanzaError().getCondition());
        assertTrue(forbidden.getStanzaError().getDescriptiveText().contains(AccessRules.LAB_GROUPS.get(
                Role.OPERATOR)), forbidden.getStanzaError().toString());
        Map<Map<String, String>, String> bad = Map.of(
                Map.of("device", "not a jid@@"), "device: expected a bare JID",
                Map.of("device", robotJid + "/onboard"), "device: expected a bare JID",
                Map.of("device", robotJid.toString(), "max", "501"), "max: expected 1..500 commands",
                Map.of("device", robotJid.toString(), "max", "x"), "max: expected 1..500 commands",
                Map.of("device", robotJid.toString(), "before", "-1"), "before: expected a command's seq");
        List<String> unexpected = new ArrayList<>();
        for (var request : bad.entrySet()) {
            XMPPErrorException e = assertThrows(XMPPErrorException.class, () -> operator
                    .sendIqRequestAndWaitForResponse(historyIq(IQ.Type.get, request.getKey())));
            if (e.getStanzaError().getCondition() != StanzaError.Condition.bad_request || !e.getStanzaError()
                    .getDescriptiveText().contains(request.getValue())) {
                unexpected.add(request.getKey() + ": " + e.getStanzaError());
            }
        }
        assertEquals(List.of(), unexpected);
        XMPPErrorException set = assertThrows(XMPPErrorException.class, () -> operator.sendIqRequestAndWaitForResponse(
                historyIq(IQ.Type.set, Map.of("device", robotJid.toString()))));
        assertEquals(StanzaError.Condition.not_allowed, set.getStanzaError().getCondition());
        assertEquals(4, CommandHistory.read(operator, robotJid, CommandHistory.MAX).size(), "a refusal changed it");
    }

    /** A history request with any attributes, as a client that does not use {@link CommandHistory} may send. */
    private static IQ historyIq(IQ.Type type, Map<String, String> attributes) {
        IQ iq = new IQ(CommandHistory.ELEMENT, CommandHistory.NAMESPACE) {
            @Override
            protected IQChildElementXmlStringBuilder getIQChildElementBuilder(IQChildElementXmlStringBuilder xml) {
                attributes.forEach(xml::attribute);
                xml.setEmptyElement();
        return xml;
            }
        };
        iq.setType(type);
        iq.setTo(PrivateXmppServer.domainJid(PrivateXmppServer.DOMAIN));
        return iq;
    }

    private static XMPPTCPConnection login(String localpart) throws Exception {
        return XMPP.connect(XMPP.configuration(localpart, PrivateXmppServer.DOMAIN, PASSWORD).build());
    }

    /**
     * Polls the archive until it holds at least {@code rows} rows for the arguments: the server writes them every
     * 200 ms, in a database that is another process (there is no event to wait on).
     */
    private static List<String> awaitRows(int rows, String... arguments) throws Exception {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);
        List<String> got = XMPP.archiveLog(arguments);
        while (got.size() < rows && System.nanoTime() < deadline) {
            Thread.sleep(50);
            got = XMPP.archiveLog(arguments);
        }
        return got;
    }

    private static final Pattern FIELD = Pattern.compile("\"([a-z_]+)\" ?: ?(\"((?:[^\"\\\\]|\\\\.)*)\"|[0-9.]+|null)");

    /** A field of a JSON line (the log's objects are flat: strings, numbers, null). */
    private static String field(String json, String name) {
        Matcher m = FIELD.matcher(json);
        while (m.find()) {
            if (m.group(1).equals(name)) {
                return m.group(3) != null ? m.group(3) : m.group(2);
            }
        }
        throw new AssertionError("no field " + name + " in " + json);
    }
}
