package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.lang.reflect.Field;
import java.net.Socket;
import java.time.Duration;
import java.time.Instant;
import java.time.LocalDate;
import java.util.Calendar;
import java.util.List;
import java.util.Map;
import java.util.TimeZone;
import java.util.concurrent.ArrayBlockingQueue;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;

import org.jivesoftware.smack.StanzaCollector;
import org.jivesoftware.smack.iqrequest.AbstractIqRequestHandler;
import org.jivesoftware.smack.iqrequest.IQRequestHandler;
import org.jivesoftware.smack.packet.IQ;
import org.jivesoftware.smack.packet.Message;
import org.jivesoftware.smack.packet.StanzaError.Condition;
import org.jivesoftware.smack.packet.StanzaError;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smackx.mam.MamManager;
import org.jivesoftware.smackx.time.packet.Time;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.TestInfo;
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.Jid;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlError;
import sabot.controlml.ControlMlManager;
import sabot.controlml.ControlMlType;
import sabot.controlml.Outcome;
import sabot.controlml.PendingCommand;
import sabot.controlml.RequestId;
import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.StaleCommandPolicy;
import sabot.controlml.TelemetryLeases;
import sabot.controlml.TelemetryManager;
import sabot.controlml.TelemetryPublication;
import sabot.controlml.TelemetryWatcher;
import sabot.controlml.payload.AccessRole;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.NoQuery;
import sabot.controlml.payload.PayloadCodec;
import sabot.controlml.payload.PoseEstimate;
import sabot.controlml.payload.TelemetryRates;
import sabot.controlml.payload.TelemetryRates.StreamRate;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.xmpp.PrivateXmppServer;
import sabot.testsupport.xmpp.Subscriptions;

/**
 * ControlML between a robot and workbenches through a real, unmodified server: every get/set/result/error path,
 * authorization, bad input over the wire, cross-domain, offline delivery with the stale-command policy, archive,
 * stream-management resumption and PEP telemetry. Subclasses pick the server.
 */
abstract class ControlMlOnServerTest {

    static final long TIMEOUT_S = 10;
    static final Goal NEW_GOAL = new Goal(new Pose2D(7, -1, 0.5), 0.1, 0.2);

    protected abstract PrivateXmppServer server();

    @BeforeAll
    static void streamManagement() {
        XMPPTCPConnection.setUseStreamManagementDefault(true);
        XMPPTCPConnection.setUseStreamManagementResumptionDefault(true);
    }

    /** A robot connection with every resource served and the given requesters' rights. */
    record Robot(XMPPTCPConnection connection, RecordingDevice device, ControlMlManager manager) {
        Jid jid() {
            return connection.getUser();
        }
    }

    static String unique(TestInfo info, String role) {
        return role + "-" + Integer.toHexString(info.getDisplayName().hashCode() & 0xffffff);
    }

    Robot robot(XMPPTCPConnection connection, Map<Jid, Role> rights) {
        RecordingDevice device = new RecordingDevice();
        ControlMlManager m = ControlMlManager.getInstanceFor(connection);
        device.registerOn(m);
        m.setAccessPolicy(j -> rights.getOrDefault(j.asBareJid(), Role.NONE));
        return new Robot(connection, device, m);
    }

    @Test
    void workbenchGetsAndSetsEveryResourceThroughTheServer(TestInfo info) throws Exception {
        XMPPTCPConnection wb = server().login(unique(info, "wb"));
        Robot robot = robot(server().login(unique(info, "robot")), Map.of(wb.getUser().asBareJid(), Role.MAINTAINER));
        ControlMlManager client = ControlMlManager.getInstanceFor(wb);

        for (Resource<?, ?> r : Resources.all()) {
            if (r.isGettable()) {
                Outcome<?> got = getAny(client, robot.jid(), r);
                // cm.role: the workbench's own role there, not a stored value
                assertEquals(r == Resources.ROLE ? new AccessRole(Role.MAINTAINER) : Samples.VALUES.get(r), got
                        .orElseThrow(), r.name());
            }
            if (r.isSettable()) {
                Outcome<?> set = setAny(client, robot.jid(), r, Samples.VALUES.get(r));
                assertTrue(set.isSuccess(), () -> r.name() + ": " + set);
            }
        }
        assertEquals(Resources.all().stream().filter(Resource::isSettable).count(), robot.device().applied.size());

        assertTrue(client.set(robot.jid(), Resources.GOAL, NEW_GOAL).isSuccess());
        assertEquals(NEW_GOAL, robot.device().state.get("cm.goal"));
        assertEquals(NEW_GOAL, client.get(robot.jid(), Resources.GOAL).orElseThrow());
    }

    @Test
    void aRegisteredResourceOfAnotherBundleTravels(TestInfo info) throws Exception {
        XMPPTCPConnection wb = server().login(unique(info, "wb"));
        Robot robot = robot(server().login(unique(info, "robot")), Map.of(wb.getUser().asBareJid(), Role.MAINTAINER));
        ControlMlManager client = ControlMlManager.getInstanceFor(wb);
        ResourceRegistryTest.Counter seven = new ResourceRegistryTest.Counter(7);
        assertEquals(sabot.controlml.ControlMlCondition.UNKNOWN_RESOURCE, client.set(robot.jid(),
                ResourceRegistryTest.COUNTER, seven).errorOrNull().cmCondition(), "not registered on the robot yet");

        robot.manager().resources().register(ResourceRegistryTest.COUNTER);
        java.util.concurrent.atomic.AtomicReference<ResourceRegistryTest.Counter> state =
                new java.util.concurrent.atomic.AtomicReference<>(new ResourceRegistryTest.Counter(0));
        robot.manager().onSet(ResourceRegistryTest.COUNTER, (r, c) -> {
            state.set(c);
            return Outcome.success(c);
        });
        // the requester needs the resource object only, not a registration of its own
        assertEquals(seven, client.set(robot.jid(), ResourceRegistryTest.COUNTER, seven).orElseThrow());
        assertEquals(seven, state.get());
        assertEquals(sabot.controlml.ControlMlCondition.UNSUPPORTED_OPERATION, client.get(robot.jid(),
                ResourceRegistryTest.COUNTER).errorOrNull()
                .cmCondition(), "registered, but this robot serves no get of it");
    }

    @SuppressWarnings("unchecked")
    private static <T, Q> Outcome<T> getAny(ControlMlManager client, Jid robot, Resource<T, Q> r) {
        return r.queryCodec() == null ? client.get(robot, (Resource<T, NoQuery>) r) : client.get(robot, r,
                (Q) Samples.QUERY);
    }

    @SuppressWarnings("unchecked")
    private static <T> Outcome<T> setAny(ControlMlManager client, Jid robot, Resource<T, ?> r, Object value) {
        return client.set(robot, r, (T) value);
    }

    @Test
    void errorsArriveAsValuesWithTheirConditions(TestInfo info) throws Exception {
        XMPPTCPConnection wb = server().login(unique(info, "wb"));
        Robot robot = robot(server().login(unique(info, "robot")), Map.of(wb.getUser().asBareJid(), Role.MAINTAINER));
        ControlMlManager client = ControlMlManager.getInstanceFor(wb);
        robot.manager().removeHandlers(Resources.MAP);
        robot.manager().onSet(Resources.GOAL, (r, g) -> Outcome.failure(ControlMlCondition.INVALID_STATE,
                "a mission is running"));

        ControlMlError notServed = client.get(robot.jid(), Resources.MAP).errorOrNull();
        assertEquals(Condition.service_unavailable, notServed.condition());
        assertEquals(ControlMlCondition.UNSUPPORTED_OPERATION, notServed.cmCondition());

        ControlMlError refused = client.set(robot.jid(), Resources.GOAL, NEW_GOAL).errorOrNull();
        assertEquals(Condition.unexpected_request, refused.condition());
        assertEquals(ControlMlCondition.INVALID_STATE, refused.cmCondition());
        assertEquals("a mission is running", refused.text());

        ControlMlError unknown = client.exchange(robot.jid(), ControlMlElement.request(ControlMlType.GET,
                new RequestId(LocalDate.now(), 1), "cm.teleport", null)).errorOrNull();
        assertEquals(Condition.item_not_found, unknown.condition());
        assertEquals(ControlMlCondition.UNKNOWN_RESOURCE, unknown.cmCondition());

        // an IQ to a resource that is not online is answered by the server itself (RFC 6120 8.5.3.2.1)
        client.setRequestTimeout(Duration.ofSeconds(5));
        server().register(unique(info, "offline"), PrivateXmppServer.DOMAIN, "pw");
        ControlMlError gone = client.get(offlineFullJid(info), Resources.POSITION).errorOrNull();
        assertNotNull(gone);
        assertEquals(Condition.service_unavailable, gone.condition(), gone.toString());
        assertEquals(ControlMlCondition.UNSPECIFIED, gone.cmCondition());
    }

    private Jid offlineFullJid(TestInfo info) throws Exception {
        return org.jxmpp.jid.impl.JidCreate.from(unique(info, "offline") + "@" + PrivateXmppServer.DOMAIN
                + "/onboard");
    }

    @Test
    void unauthorizedSetIsForbiddenAndLeavesTheRobotUnchanged(TestInfo info) throws Exception {
        XMPPTCPConnection viewer = server().login(unique(info, "viewer"));
        XMPPTCPConnection stranger = server().login(unique(info, "stranger"));
        Robot robot = robot(server().login(unique(info, "robot")), Map.of(viewer.getUser().asBareJid(),
                Role.OBSERVER));

        ControlMlError setByViewer = ControlMlManager.getInstanceFor(viewer).set(robot.jid(), Resources.GOAL,
                NEW_GOAL).errorOrNull();
        ControlMlError getByStranger = ControlMlManager.getInstanceFor(stranger).get(robot.jid(),
                Resources.POSITION).errorOrNull();

        assertEquals(Condition.forbidden, setByViewer.condition());
        assertEquals(ControlMlCondition.SET_NOT_PERMITTED, setByViewer.cmCondition());
        assertEquals(Condition.forbidden, getByStranger.condition());
        assertEquals(ControlMlCondition.ACCESS_DENIED, getByStranger.cmCondition());
        assertTrue(robot.device().applied.isEmpty());
        assertEquals(Samples.POSE, ControlMlManager.getInstanceFor(viewer).get(robot.jid(), Resources.POSITION)
                .orElseThrow(), "the viewer may still read");
    }

    @Test
    void badInputOverTheWireIsRefusedAndTheConnectionSurvives(TestInfo info) throws Exception {
        XMPPTCPConnection wb = server().login(unique(info, "wb"));
        Robot robot = robot(server().login(unique(info, "robot")), Map.of(wb.getUser().asBareJid(), Role.MAINTAINER));
        String goal = ControlMlBadInputTest.goal("NaN", "m");
        String goalContent = goal.substring(goal.indexOf("<DataRecord"), goal.lastIndexOf("</control-ml>"));
        record Case(String attributes, String content, Condition condition, ControlMlCondition cm) {
        }
        List<Case> cases = List.of(
                new Case("type='set' id='20261121:1' res='cm.goal'", goalContent, Condition.not_acceptable,
                        ControlMlCondition.INVALID_VALUE),
                new Case("type='set' id='20261121:2' res='cm.goal'", goalContent.replace(">NaN<", ">1<").replace(
                        "code='m'/><value>1<", "code='s'/><value>1<"), Condition.not_acceptable,
                        ControlMlCondition.WRONG_UNIT),
                new Case("type='set' id='2026-11-21:3' res='cm.goal'", goalContent, Condition.bad_request,
                        ControlMlCondition.BAD_ID),
                new Case("type='set' res='cm.goal'", goalContent, Condition.bad_request,
                        ControlMlCondition.BAD_ATTRIBUTES),
                new Case("type='set' id='20261121:4' res='cm.goal' urgent='yes'", goalContent, Condition.bad_request,
                        ControlMlCondition.BAD_ATTRIBUTES),
                new Case("type='set' id='20261121:5' res='cm.teleport'", goalContent, Condition.item_not_found,
                        ControlMlCondition.UNKNOWN_RESOURCE),
                new Case("type='set' id='20261121:6' res='cm.goal'", "<DataRecord xmlns='http://www.opengis.net/"
                        + "swe/2.0'><field name='x'><Oops/></field></DataRecord>", Condition.bad_request,
                        ControlMlCondition.MALFORMED_PAYLOAD),
                new Case("type='set' id='20261121:7' res='cm.goal'", "<Text xmlns='http://www.opengis.net/swe/2.0'>"
                        + "<value>" + "x".repeat(70_000) + "</value></Text>", Condition.not_acceptable,
                        ControlMlCondition.PAYLOAD_TOO_LARGE),
                new Case("type='get' id='20261121:8' res='cm.goal'", "", Condition.bad_request,
                        ControlMlCondition.TYPE_MISMATCH));
        for (Case c : cases) {
            RawIQ iq = new RawIQ(IQ.Type.set, c.attributes(), c.content());
            iq.setTo(robot.jid());
            IQ answer;
            try (StanzaCollector collector = wb.createStanzaCollectorAndSend(iq)) {
                answer = collector.nextResult(TimeUnit.SECONDS.toMillis(TIMEOUT_S));
            }
            assertNotNull(answer, "no answer to " + c);
            assertEquals(IQ.Type.error, answer.getType(), c.toString());
            ControlMlError error = ControlMlError.fromStanzaError(answer.getError());
            assertEquals(c.condition(), error.condition(), c + " -> " + error);
            assertEquals(c.cm(), error.cmCondition(), c + " -> " + error);
        }
        assertTrue(robot.connection().isConnected() && wb.isConnected(), "a bad request broke a connection");
        assertTrue(robot.device().applied.isEmpty(), "state changed: " + robot.device().applied);
        assertEquals(Samples.POSE, ControlMlManager.getInstanceFor(wb).get(robot.jid(), Resources.POSITION)
                .orElseThrow());
    }

    /**
     * A request whose attributes cannot all be read is answered with the {@code <error/>} alone (section 8): no
     * {@code <control-ml/>} echoing the attributes that could be read (Smack's createErrorResponse copies the
     * request's child, which made an element without failure and with the request's type).
     */
    @Test
    void unreadableAttributesAreAnsweredWithTheErrorAlone(TestInfo info) throws Exception {
        XMPPTCPConnection wb = server().login(unique(info, "wb"));
        Robot robot = robot(server().login(unique(info, "robot")), Map.of(wb.getUser().asBareJid(), Role.MAINTAINER));
        record Case(String attributes, ControlMlCondition cm) {
        }
        List<Case> cases = List.of(
                new Case("id='20261121:1' res='cm.position'", ControlMlCondition.BAD_ATTRIBUTES),
                new Case("type='get' res='cm.position'", ControlMlCondition.BAD_ATTRIBUTES),
                new Case("type='get' id='20261121:1'", ControlMlCondition.BAD_ATTRIBUTES),
                new Case("type='put' id='20261121:1' res='cm.position'", ControlMlCondition.BAD_ATTRIBUTES),
                new Case("type='get' id='2026-11-21:1' res='cm.position'", ControlMlCondition.BAD_ID),
                new Case("type='get' id='20261332:1' res='cm.position'", ControlMlCondition.BAD_ID),
                new Case("type='get' id='20261121:4294967296' res='cm.position'", ControlMlCondition.BAD_ID),
                new Case("type='get' id='20261121:01' res='cm.position'", ControlMlCondition.BAD_ID),
                new Case("type='get' id='20261121:1' res='Position'", ControlMlCondition.BAD_ATTRIBUTES));
        for (IQ.Type iqType : new IQ.Type[] { IQ.Type.get, IQ.Type.set }) {
            for (Case c : cases) {
                String attributes = iqType == IQ.Type.set ? c.attributes().replace("'get'", "'set'") : c.attributes();
                RawIQ iq = new RawIQ(iqType, attributes, "");
                iq.setTo(robot.jid());
                IQ answer;
                try (StanzaCollector collector = wb.createStanzaCollectorAndSend(iq)) {
                    answer = collector.nextResult(TimeUnit.SECONDS.toMillis(TIMEOUT_S));
                }
                assertNotNull(answer, "no answer to " + attributes);
                assertInstanceOf(org.jivesoftware.smack.packet.ErrorIQ.class, answer, () -> iqType + " " + attributes
                        + " -> " + answer.toXML());
                ControlMlError error = ControlMlError.fromStanzaError(answer.getError());
                assertEquals(Condition.bad_request, error.condition(), attributes);
                assertEquals(c.cm(), error.cmCondition(), attributes);
            }
        }
        assertTrue(robot.device().applied.isEmpty());
    }

    /**
     * The RFC 6120 {@code <text/>} of every error answer arrives as the stanza error's descriptive text (in the
     * stanzas namespace, {@code xml:lang='en'}), not only as the copy inside {@code <control-ml/>}: for a handler's
     * refusal, for a request whose attributes cannot be read (bare {@code <error/>}, nothing to echo) and for a bounced
     * message. Smack 4.4.8's writer used to drop the text's namespace (see DescriptiveText).
     */
    @Test
    void stanzaErrorsCarryTheirDescriptiveText(TestInfo info) throws Exception {
        XMPPTCPConnection wb = server().login(unique(info, "wb"));
        Robot robot = robot(server().login(unique(info, "robot")), Map.of(wb.getUser().asBareJid(), Role.MAINTAINER));
        String why = "a mission is running <since 10:15> & 'cannot' stop";
        robot.manager().onSet(Resources.GOAL, (r, g) -> Outcome.failure(ControlMlCondition.INVALID_STATE, why));

        // 1. a handler's refusal, with the echoed control-ml
        sabot.controlml.ControlMlIQ request = new sabot.controlml.ControlMlIQ(ControlMlElement.request(
                ControlMlType.SET, new RequestId(LocalDate.now(), 4711), "cm.goal", Resources.GOAL.codec().encode(
                        NEW_GOAL)).withSent(Instant.now()));
        request.setTo(robot.jid());
        IQ refused;
        try (StanzaCollector collector = wb.createStanzaCollectorAndSend(request)) {
            refused = collector.nextResult(TimeUnit.SECONDS.toMillis(TIMEOUT_S));
        }
        assertNotNull(refused, "no answer");
        assertEquals(IQ.Type.error, refused.getType());
        org.jivesoftware.smack.packet.StanzaError error = refused.getError();
        assertEquals(Condition.unexpected_request, error.getCondition());
        assertEquals(why, error.getDescriptiveText("en"), error.toXML().toString());
        assertNotNull(error.getExtension(ControlMlCondition.INVALID_STATE.element(),
                sabot.controlml.ControlMl.ERRORS_NAMESPACE), error.toXML().toString());
        assertNull(error.getExtension("text", "jabber:client"), "text without its namespace: " + error.toXML());
        ControlMlError viaStanzaError = ControlMlError.fromStanzaError(error);
        assertEquals(ControlMlError.of(ControlMlCondition.INVALID_STATE, why), viaStanzaError);
        assertEquals(viaStanzaError, ((sabot.controlml.ControlMlIQ) refused).element().failure(),
                "the stanza error and the control-ml copy agree");

        // 2. unreadable attributes: only the <error/>, its text included
        RawIQ unreadable = new RawIQ(IQ.Type.set, "type='set' id='yesterday' res='cm.goal'", "");
        unreadable.setTo(robot.jid());
        IQ bare;
        try (StanzaCollector collector = wb.createStanzaCollectorAndSend(unreadable)) {
            bare = collector.nextResult(TimeUnit.SECONDS.toMillis(TIMEOUT_S));
        }
        assertNotNull(bare, "no answer");
        assertEquals(IQ.Type.error, bare.getType());
        String bareText = bare.getError().getDescriptiveText("en");
        assertNotNull(bareText, bare.getError().toXML().toString());
        assertTrue(bareText.contains("yesterday"), bareText);
        assertEquals(ControlMlCondition.BAD_ID, ControlMlError.fromStanzaError(bare.getError()).cmCondition());

        // 3. a command message whose attributes cannot be read is bounced with the same error
        Message bad = wb.getStanzaFactory().buildMessageStanza().to(robot.jid()).addExtension(
                new org.jivesoftware.smack.packet.ExtensionElement() {
                    @Override
                    public String getElementName() {
                        return "control-ml";
                    }

                    @Override
                    public String getNamespace() {
                        return sabot.controlml.ControlMl.NAMESPACE;
                    }

                    @Override
                    public String toXML(org.jivesoftware.smack.packet.XmlEnvironment env) {
                        return "<control-ml xmlns='urn:sabot:controlml:1' type='set' id='yesterday' res='cm.goal'/>";
                    }
                }).build();
        Message bounced;
        try (StanzaCollector collector = wb.createStanzaCollectorAndSend(new org.jivesoftware.smack.filter.AndFilter(
                org.jivesoftware.smack.filter.MessageTypeFilter.ERROR, org.jivesoftware.smack.filter.FromMatchesFilter
                        .createFull(robot.jid())), bad)) {
            bounced = collector.nextResult(TimeUnit.SECONDS.toMillis(TIMEOUT_S));
        }
        assertNotNull(bounced, "no bounce");
        String bouncedText = bounced.getError().getDescriptiveText("en");
        assertNotNull(bouncedText, bounced.getError().toXML().toString());
        assertTrue(bouncedText.contains("yesterday"), bouncedText);
    }

    @Test
    void unsolicitedAnswersAreLoggedAndDropped(TestInfo info) throws Exception {
        XMPPTCPConnection wb = server().login(unique(info, "wb"));
        Robot robot = robot(server().login(unique(info, "robot")), Map.of(wb.getUser().asBareJid(), Role.MAINTAINER));
        CountDownLatch drops = new CountDownLatch(2);
        robot.manager().addUnsolicitedAnswerListener((from, element) -> drops.countDown());
        ControlMlElement result = ControlMlElement.result(new RequestId(LocalDate.now(), 99), "cm.goal",
                Resources.GOAL.codec().encode(NEW_GOAL));

        sabot.controlml.ControlMlIQ iq = new sabot.controlml.ControlMlIQ(result);
        iq.setTo(robot.jid());
        iq.setStanzaId("never-asked");
        wb.sendStanza(iq);
        wb.sendStanza(wb.getStanzaFactory().buildMessageStanza().to(robot.jid()).addExtension(result).build());

        assertTrue(drops.await(TIMEOUT_S, TimeUnit.SECONDS), "unsolicited answers not dropped");
        assertEquals(2, robot.manager().statistics().unsolicitedDropped());
        assertTrue(robot.device().applied.isEmpty());
        assertEquals(Samples.POSE, ControlMlManager.getInstanceFor(wb).get(robot.jid(), Resources.POSITION)
                .orElseThrow(), "connection alive");
    }

    @Test
    void workbenchOnAnotherDomainCommandsTheRobot(TestInfo info) throws Exception {
        XMPPTCPConnection wb = server().login(unique(info, "wb"), PrivateXmppServer.SECOND_DOMAIN);
        Robot robot = robot(server().login(unique(info, "robot")), Map.of(wb.getUser().asBareJid(), Role.MAINTAINER));
        ControlMlManager client = ControlMlManager.getInstanceFor(wb);

        assertEquals(Samples.POSE, client.get(robot.jid(), Resources.POSITION).orElseThrow());
        assertTrue(client.set(robot.jid(), Resources.GOAL, NEW_GOAL).isSuccess());
        assertEquals(NEW_GOAL, robot.device().state.get("cm.goal"));
        assertEquals(PrivateXmppServer.SECOND_DOMAIN, wb.getUser().getDomain().toString());
    }

    @Test
    void setSentWhileTheRobotIsOfflineIsDeliveredLaterArchivedAndStalePolicyApplies(TestInfo info)
            throws Exception {
        XMPPTCPConnection wb = server().login(unique(info, "wb"));
        String fresh = unique(info, "robot-fresh");
        String strict = unique(info, "robot-strict");
        EntityBareJid freshJid = server().register(fresh, PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD);
        EntityBareJid strictJid = server().register(strict, PrivateXmppServer.DOMAIN,
                PrivateXmppServer.DEFAULT_PASSWORD);
        ControlMlManager client = ControlMlManager.getInstanceFor(wb);

        PendingCommand<Goal> toFresh = client.sendCommandMessage(freshJid, Resources.GOAL, NEW_GOAL);
        PendingCommand<Goal> toStrict = client.sendCommandMessage(strictJid, Resources.GOAL, NEW_GOAL);

        // The server has the commands (they are in the workbench's archive, XEP-0313) before the robots come online;
        // otherwise a robot logging in at the same moment could race the server's offline store.
        assertArchived(wb, freshJid, toFresh.id());
        assertArchived(wb, strictJid, toStrict.id());

        // The robots come online later; their endpoints are ready before login, when the server flushes the store.
        Robot freshRobot = offlineRobotComesOnline(fresh, wb, StaleCommandPolicy.DEFAULT);
        Robot strictRobot = offlineRobotComesOnline(strict, wb, StaleCommandPolicy.refuseOlderThan(Duration
                .ofMillis(1)));

        Outcome<Goal> applied = toFresh.outcome().get(TIMEOUT_S, TimeUnit.SECONDS);
        Outcome<Goal> refused = toStrict.outcome().get(TIMEOUT_S, TimeUnit.SECONDS);
        assertTrue(applied.isSuccess(), applied::toString);
        assertEquals(NEW_GOAL, freshRobot.device().state.get("cm.goal"));
        assertEquals(List.of("cm.goal " + toFresh.id()), freshRobot.device().applied);
        assertEquals(ControlMlCondition.STALE_COMMAND, refused.errorOrNull().cmCondition());
        assertEquals(Condition.not_acceptable, refused.errorOrNull().condition());
        assertTrue(strictRobot.device().applied.isEmpty());
    }

    /** Queries the workbench's archive until the command is there (each query is a round trip; no sleeping). */
    private static void assertArchived(XMPPTCPConnection wb, EntityBareJid with, RequestId id) throws Exception {
        MamManager.MamQueryArgs query = MamManager.MamQueryArgs.builder().limitResultsToJid(with)
                .setResultPageSizeTo(50).build();
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);
        List<Message> archived = List.of();
        while (System.nanoTime() < deadline) {
            archived = MamManager.getInstanceFor(wb).queryArchive(query).getMessages();
            if (archived.stream().map(m -> m.getExtension(ControlMlElement.class)).anyMatch(e -> e != null && e
                    .type() == ControlMlType.SET && id.equals(e.id()))) {
                return;
            }
        }
        throw new AssertionError("command " + id + " not in the archive: " + archived);
    }

    /**
     * Section 5: a stored command that arrives at the login, before the device's code has registered the handler of
     * its resource (a robot whose tasks still start), is held and applied once the handler is registered.
     */
    @Test
    void aStoredCommandThatArrivesBeforeItsHandlerIsAppliedOnceTheHandlerIsThere(TestInfo info) throws Exception {
        XMPPTCPConnection wb = server().login(unique(info, "wb"));
        String name = unique(info, "robot");
        EntityBareJid robotJid = server().register(name, PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD);
        PendingCommand<Goal> sent = ControlMlManager.getInstanceFor(wb).sendCommandMessage(robotJid, Resources.GOAL,
                NEW_GOAL);
        assertArchived(wb, robotJid, sent.id()); // stored before the robot logs in

        XMPPTCPConnection c = new XMPPTCPConnection(server().configuration(name, PrivateXmppServer.DOMAIN,
                PrivateXmppServer.DEFAULT_PASSWORD).setResource("onboard").build());
        ControlMlManager manager = ControlMlManager.getInstanceFor(c);
        BareJid operator = wb.getUser().asBareJid();
        manager.setAccessPolicy(j -> j.asBareJid().equals(operator) ? Role.MAINTAINER : Role.NONE);
        CountDownLatch arrived = new CountDownLatch(1);
        c.addSyncStanzaListener(stanza -> arrived.countDown(), stanza -> stanza instanceof Message && stanza
                .getExtension(ControlMlElement.class) != null);
        c.connect().login();
        closeAfterClass.add(c);
        assertTrue(arrived.await(TIMEOUT_S, TimeUnit.SECONDS), "the stored command never arrived");
        assertFalse(sent.outcome().isDone(), "answered before the robot serves cm.goal: " + sent.outcome());

        List<Goal> applied = new java.util.concurrent.CopyOnWriteArrayList<>();
        manager.onSet(Resources.GOAL, (request, goal) -> {
            applied.add(goal);
            return Outcome.done();
        });
        Outcome<Goal> outcome = sent.outcome().get(TIMEOUT_S, TimeUnit.SECONDS);
        assertTrue(outcome.isSuccess(), outcome::toString);
        assertEquals(List.of(NEW_GOAL), applied);
    }

    private Robot offlineRobotComesOnline(String localpart, XMPPTCPConnection wb, StaleCommandPolicy policy)
            throws Exception {
        XMPPTCPConnection c = new XMPPTCPConnection(server().configuration(localpart, PrivateXmppServer.DOMAIN,
                PrivateXmppServer.DEFAULT_PASSWORD).setResource("onboard").build());
        Robot robot = robot(c, Map.of(wb.getUser().asBareJid(), Role.MAINTAINER));
        robot.manager().setStaleCommandPolicy(policy);
        c.connect().login();
        closeAfterClass.add(c);
        return robot;
    }

    static final List<XMPPTCPConnection> closeAfterClass = new java.util.concurrent.CopyOnWriteArrayList<>();

    @org.junit.jupiter.api.AfterAll
    static void closeOwnConnections() {
        closeAfterClass.forEach(XMPPTCPConnection::instantShutdown);
        closeAfterClass.clear();
    }

    /**
     * Section 5: a set the server held for the robot's hibernated session (XEP-0198) and delivered on resumption is
     * judged by its send time: older than the robot accepts, it is refused as stale and never applied; the
     * requester's retry under the same id gets the same answer from the replay cache.
     */
    @Test
    void aSetHeldDuringALinkDropIsRefusedAsStaleOnResumption(TestInfo info) throws Exception {
        XMPPTCPConnection wb = server().login(unique(info, "wb"));
        Robot robot = robot(server().login(unique(info, "robot")), Map.of(wb.getUser().asBareJid(), Role.MAINTAINER));
        Duration limit = Duration.ofSeconds(1);
        robot.manager().setStaleCommandPolicy(StaleCommandPolicy.refuseOlderThan(limit));
        assertTrue(robot.connection().isSmResumptionPossible(), "server did not offer resumption");
        ControlMlManager client = ControlMlManager.getInstanceFor(wb);
        Instant sent = Instant.now();
        ControlMlElement command = ControlMlElement.request(ControlMlType.SET, new RequestId(LocalDate.now(), 4242),
                "cm.goal", Resources.GOAL.codec().encode(NEW_GOAL)).withSent(sent);

        socketOf(robot.connection()).close(); // the robot's network drops
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);
        while (robot.connection().isConnected() && System.nanoTime() < deadline) {
            Thread.onSpinWait(); // Smack notices the dead socket on its reader thread
        }
        assertTrue(robot.connection().isDisconnectedButSmResumptionPossible());
        // The server still thinks the robot is there: it queues the set for the hibernating session.
        CompletableFuture<Outcome<ControlMlElement>> first = CompletableFuture.supplyAsync(() -> client.exchange(robot
                .jid(), command));
        // the link stays down longer than the robot accepts a command's age (the condition under test, not a wait
        // for something to happen)
        Thread.sleep(Math.max(0, Duration.between(Instant.now(), sent.plus(limit).plusMillis(200)).toMillis()));
        robot.connection().connect();
        robot.connection().login();
        assertTrue(robot.connection().streamWasResumed(), "stream was not resumed");

        Outcome<ControlMlElement> answer = first.get(TIMEOUT_S + 5, TimeUnit.SECONDS);
        Outcome<ControlMlElement> retry = client.exchange(robot.jid(), command); // same ControlML id, new stanza

        assertEquals(ControlMlCondition.STALE_COMMAND, answer.errorOrNull().cmCondition(), answer::toString);
        assertEquals(ControlMlCondition.STALE_COMMAND, retry.errorOrNull().cmCondition(), retry::toString);
        assertTrue(robot.device().applied.isEmpty(), "a held command was applied: " + robot.device().applied);
        assertEquals(1, robot.manager().statistics().duplicatesReplayed());
    }

    /**
     * Section 5's clock rule over a real server: a requester whose clock runs an hour ahead (its XEP-0202 answer and
     * its send times both) is measured when its presence arrives, and its sets are judged on its own clock.
     */
    @Test
    void aRequesterWhoseClockIsAnHourAheadIsJudgedOnItsOwnClock(TestInfo info) throws Exception {
        Duration ahead = Duration.ofHours(1);
        XMPPTCPConnection wb = server().login(unique(info, "wb"));
        ControlMlManager client = ControlMlManager.getInstanceFor(wb);
        // its own XEP-0202 answer replaces Smack's: the workbench's clock, an hour ahead
        wb.registerIQRequestHandler(new AbstractIqRequestHandler(Time.ELEMENT, Time.NAMESPACE, IQ.Type.get,
                IQRequestHandler.Mode.async) {
            @Override
            public IQ handleIQRequest(IQ request) {
                Calendar c = Calendar.getInstance(TimeZone.getTimeZone("UTC"));
                c.setTimeInMillis(Instant.now().plus(ahead).toEpochMilli());
                Time t = new Time(c);
                t.setType(IQ.Type.result);
                t.setTo(request.getFrom());
                t.setStanzaId(request.getStanzaId());
                return t;
            }
        });
        Robot robot = robot(server().login(unique(info, "robot")), Map.of(wb.getUser().asBareJid(), Role.MAINTAINER));
        Subscriptions.mutual(wb, robot.connection(), Duration.ofSeconds(TIMEOUT_S));
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);
        Duration measured;
        while ((measured = robot.manager().clockOffsetOf(wb.getUser())) == null && System.nanoTime() < deadline) {
            Thread.onSpinWait(); // the robot asks for the workbench's time when its presence arrives
        }
        assertNotNull(measured, "the robot never measured the workbench's clock");
        assertTrue(measured.minus(ahead).abs().toMillis() < 1000, "offset " + measured);

        RequestId fresh = new RequestId(LocalDate.now(), 77);
        Outcome<ControlMlElement> a = client.exchange(robot.jid(), ControlMlElement.request(ControlMlType.SET, fresh,
                "cm.goal", Resources.GOAL.codec().encode(NEW_GOAL)).withSent(Instant.now().plus(ahead)));
        assertTrue(a.isSuccess(), "a set sent now on the workbench's clock: " + a);
        Outcome<ControlMlElement> old = client.exchange(robot.jid(), ControlMlElement.request(ControlMlType.SET,
                new RequestId(LocalDate.now(), 78), "cm.goal", Resources.GOAL.codec().encode(NEW_GOAL)).withSent(
                        Instant.now().plus(ahead).minusSeconds(60)));
        assertEquals(ControlMlCondition.STALE_COMMAND, old.errorOrNull().cmCondition(), old::toString);
        java.util.regex.Matcher offset = java.util.regex.Pattern.compile("your clock differs by (\\d+) ms").matcher(old
                .errorOrNull().text());
        assertTrue(offset.find() && Math.abs(Long.parseLong(offset.group(1)) - ahead.toMillis()) < 1000, old
                .errorOrNull().text());
        assertEquals(List.of("cm.goal " + fresh), robot.device().applied);
    }

    private static Socket socketOf(XMPPTCPConnection connection) throws ReflectiveOperationException {
        Field f = XMPPTCPConnection.class.getDeclaredField("socket");
        f.setAccessible(true);
        return (Socket) f.get(connection);
    }

    @Test
    void telemetryReachesASubscribedWorkbenchThroughPep(TestInfo info) throws Exception {
        XMPPTCPConnection wb = workbench(info);
        BlockingQueue<PoseEstimate> poses = new ArrayBlockingQueue<>(1000);
        AtomicInteger fromOthers = new AtomicInteger();
        Robot robot = robot(server().login(unique(info, "robot")), Map.of());
        TelemetryManager.getInstanceFor(wb).addListener(Resources.POSITION, (device, pose) -> {
            if (device.equals(robot.jid().asEntityBareJidIfPossible())) {
                poses.offer(pose);
            } else {
                fromOthers.incrementAndGet();
            }
        }); // before login: +notify goes into the entity caps
        wb.connect().login();
        Subscriptions.mutual(wb, robot.connection(), Duration.ofSeconds(TIMEOUT_S));

        ControlMlManager wbManager = ControlMlManager.getInstanceFor(wb);
        EntityBareJid robotBare = robot.jid().asEntityBareJidIfPossible();
        Outcome<Void> early = wbManager.telemetry().follow(robotBare, Resources.POSITION);
        assertEquals(StanzaError.Condition.item_not_found, assertInstanceOf(Outcome.Failure.class, early).error()
                .condition(), "no node before the first publication: " + early);

        AtomicInteger tick = new AtomicInteger();
        try (TelemetryPublication p = robot.manager().telemetry().publish(Resources.POSITION, () -> new PoseEstimate(
                Samples.T.plusMillis(tick.incrementAndGet()), new Pose2D(tick.get(), 0, 0), Samples.POSE.covariance()),
                50)) {
            // Besides +notify, an explicit XEP-0060 subscription to the robot's telemetry node: ejabberd 23.01 now
            // and then never honours +notify for a contact (see SmackSmokeTest), the explicit one it always does.
            followOncePublished(wbManager, robotBare);
            for (int i = 0; i < 5; i++) {
                PoseEstimate p1 = poses.poll(TIMEOUT_S, TimeUnit.SECONDS);
                assertNotNull(p1, "telemetry item " + i + " missing");
                assertEquals(Samples.POSE.covariance(), p1.covariance());
            }
        }
        assertEquals(0, fromOthers.get());
        // acknowledgements are counted asynchronously
        assertEquals(0, robot.manager().telemetry().statistics().failed());
    }

    /**
     * Section 6's recipe for a client that comes back: the listener before login (+notify), the mutual presence
     * subscription it already has, and an explicit subscription again. Prosody 0.12 then delivers every item twice
     * (for the caps and for the subscription); the receiver takes each publication once, by its control-ml id.
     */
    @Test
    void aReturningClientTakesEveryTelemetryItemOnce(TestInfo info) throws Exception {
        String wbName = unique(info, "wb");
        server().register(wbName, PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD);
        Robot robot = robot(server().login(unique(info, "robot")), Map.of());
        EntityBareJid robotBare = robot.jid().asEntityBareJidIfPossible();
        java.util.List<Double> xs = java.util.Collections.synchronizedList(new java.util.ArrayList<>());
        BlockingQueue<Double> arrived = new ArrayBlockingQueue<>(1000);
        for (int session = 0; session < 2; session++) {
            XMPPTCPConnection wb = new XMPPTCPConnection(server().configuration(wbName, PrivateXmppServer.DOMAIN,
                    PrivateXmppServer.DEFAULT_PASSWORD).build());
            closeAfterClass.add(wb);
            TelemetryManager.getInstanceFor(wb).addListener(Resources.POSITION, (device, pose) -> {
                xs.add(pose.pose().x());
                arrived.offer(pose.pose().x());
            });
            wb.connect().login();
            if (session == 0) {
                Subscriptions.mutual(wb, robot.connection(), Duration.ofSeconds(TIMEOUT_S));
                robot.manager().telemetry().publishNow(Resources.POSITION, poseAt(1));
                followOncePublished(ControlMlManager.getInstanceFor(wb), robotBare);
                wb.disconnect();
                continue;
            }
            assertTrue(TelemetryManager.getInstanceFor(wb).follow(robotBare, Resources.POSITION)
                    .isSuccess());
            for (int x = 101; x <= 106; x++) {
                robot.manager().telemetry().publishNow(Resources.POSITION, poseAt(x));
            }
            long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);
            Double x;
            do {
                x = arrived.poll(Math.max(1, deadline - System.nanoTime()), TimeUnit.NANOSECONDS);
                assertNotNull(x, "telemetry missing: " + xs);
            } while (x != 106);
            // an item delivered twice is sent before the next publication's: after 106 the second copy of each
            // earlier one would have arrived; publish once more and wait for it to be sure of 106's own copy
            robot.manager().telemetry().publishNow(Resources.POSITION, poseAt(107));
            do {
                x = arrived.poll(Math.max(1, deadline - System.nanoTime()), TimeUnit.NANOSECONDS);
                assertNotNull(x, "telemetry missing: " + xs);
            } while (x != 107);
        }
        assertEquals(List.of(101.0, 102.0, 103.0, 104.0, 105.0, 106.0, 107.0), xs.stream().filter(x -> x > 100)
                .toList(), "every publication once, in order");
    }

    /** A workbench's connection on a new account of the test, not yet connected; closed after the class. */
    XMPPTCPConnection workbench(TestInfo info) throws Exception {
        String name = unique(info, "wb");
        server().register(name, PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD);
        XMPPTCPConnection wb = new XMPPTCPConnection(server().configuration(name, PrivateXmppServer.DOMAIN,
                PrivateXmppServer.DEFAULT_PASSWORD).build());
        closeAfterClass.add(wb);
        return wb;
    }

    static PoseEstimate poseAt(double x) {
        return new PoseEstimate(Samples.T, new Pose2D(x, 0, 0), Samples.POSE.covariance());
    }

    /**
     * Section 6's leases through the server: a robot publishes at its base rate until a watcher (an observer) leases
     * a faster one, keeps it while the watcher renews, and falls back when the lease is ended, runs out, or the
     * watcher goes offline; what the robot does not publish is granted 0 Hz; a stranger's lease changes nothing.
     */
    @Test
    void telemetryIsFastOnlyWhileAWatcherLeasesIt(TestInfo info) throws Exception {
        XMPPTCPConnection wb = workbench(info);
        BlockingQueue<Long> arrivals = new LinkedBlockingQueue<>();
        Robot robot = robot(server().login(unique(info, "robot")), Map.of());
        TelemetryManager.getInstanceFor(wb).addListener(Resources.POSITION, (device, pose) -> arrivals.offer(System
                .nanoTime()));
        wb.connect().login();
        XMPPTCPConnection stranger = server().login(unique(info, "stranger"));
        robot.manager().setAccessPolicy(j -> j.asBareJid().equals(wb.getUser().asBareJid()) ? Role.OBSERVER
                : Role.NONE);
        Subscriptions.mutual(wb, robot.connection(), Duration.ofSeconds(TIMEOUT_S));
        ControlMlManager watcher = ControlMlManager.getInstanceFor(wb);
        AtomicInteger tick = new AtomicInteger();
        try (TelemetryLeases leases = robot.manager().telemetry().serveLeases(2)) {
            leases.offer(Resources.POSITION, () -> poseAt(tick.incrementAndGet()), 2, 25);
            followOncePublished(watcher, robot.jid().asEntityBareJidIfPossible());
            assertEquals(new TelemetryRates(2, List.of(new StreamRate("cm.position", 2))), watcher.get(robot.jid(),
                    Resources.TELEMETRY).orElseThrow(), "base rate, the longest lease");
            assertTrue(secondsFor(arrivals, 3) > 0.8, "3 items at the base rate of 2 Hz take a second");

            // refused, nothing changed: a stranger
            assertEquals(ControlMlCondition.ACCESS_DENIED, ControlMlManager.getInstanceFor(stranger).set(robot.jid(),
                    Resources.TELEMETRY, new TelemetryRates(1, List.of(new StreamRate("cm.position", 25))))
                    .errorOrNull().cmCondition());
            assertEquals(0, leases.watchers());
            assertEquals(2, leases.rates().stream("cm.position").rate());

            // a lease: granted up to the full rate, cut to the longest lease; what the robot does not publish at 0 Hz
            TelemetryRates granted = watcher.set(robot.jid(), Resources.TELEMETRY, new TelemetryRates(60, List.of(
                    new StreamRate("cm.position", 100), new StreamRate("cm.obstacles", 5)))).orElseThrow();
            assertEquals(new TelemetryRates(2, List.of(new StreamRate("cm.position", 25), new StreamRate(
                    "cm.obstacles", 0))), granted);
            arrivals.clear();
            assertTrue(secondsFor(arrivals, 10) < 0.8, "10 items at 25 Hz take 0.4 s");
            // ... it runs out (2 s, not renewed): the base rate again
            long until = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);
            while (leases.watchers() > 0 && System.nanoTime() < until) {
                arrivals.poll(100, TimeUnit.MILLISECONDS);
            }
            assertEquals(0, leases.watchers(), "the lease ran out");
            assertEquals(2, leases.rates().stream("cm.position").rate());

            // a watcher renews for longer than one lease: fast all along; ended by closing it
            try (TelemetryWatcher w = watcher.telemetry().watcher(2)) {
                w.watch(robot.jid(), Map.of(Resources.POSITION, 20.0));
                waitFor(() -> leases.watchers() == 1, "lease taken");
                long renewedUntil = System.nanoTime() + TimeUnit.MILLISECONDS.toNanos(3500);
                while (System.nanoTime() < renewedUntil) {
                    assertEquals(1, leases.watchers(), "renewed before it runs out");
                    assertEquals(20, leases.rates().stream("cm.position").rate());
                    arrivals.poll(100, TimeUnit.MILLISECONDS);
                }
            }
            waitFor(() -> leases.watchers() == 0, "a closed watcher ends its leases");

            // the watcher going offline ends its lease at once
            assertTrue(watcher.set(robot.jid(), Resources.TELEMETRY, new TelemetryRates(2, List.of(new StreamRate(
                    "cm.position", 25)))).isSuccess());
            assertEquals(1, leases.watchers());
            wb.disconnect();
            waitFor(() -> leases.watchers() == 0 && leases.rates().stream("cm.position").rate() == 2,
                    "offline: base rate");
        }
    }

    /** @return the seconds until {@code n} more items arrived */
    private static double secondsFor(BlockingQueue<Long> arrivals, int n) throws InterruptedException {
        long start = System.nanoTime();
        for (int i = 0; i < n; i++) {
            assertNotNull(arrivals.poll(TIMEOUT_S, TimeUnit.SECONDS), "telemetry item " + i + " of " + n);
        }
        return (System.nanoTime() - start) / 1e9;
    }

    private static void waitFor(java.util.function.BooleanSupplier condition, String what)
            throws InterruptedException {
        long until = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);
        while (!condition.getAsBoolean()) {
            assertTrue(System.nanoTime() < until, what);
            Thread.sleep(10);
        }
    }

    /** Follows a robot's cm.position telemetry once its first publication has created the node. */
    private static void followOncePublished(ControlMlManager manager, EntityBareJid robot) {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);
        while (true) {
            Outcome<Void> followed = manager.telemetry().follow(robot, Resources.POSITION);
            if (followed.isSuccess()) {
                return;
            }
            ControlMlError error = ((Outcome.Failure<Void>) followed).error();
            // the node does not exist before the first publication (every 20 ms): ask again
            if (error.condition() != StanzaError.Condition.item_not_found || System.nanoTime() > deadline) {
                throw new AssertionError("following telemetry failed: " + error);
            }
        }
    }
}
