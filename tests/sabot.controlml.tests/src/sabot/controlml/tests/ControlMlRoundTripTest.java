package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.LocalDate;
import java.util.stream.Stream;

import org.jivesoftware.smack.packet.IQ;
import org.jivesoftware.smack.packet.StanzaError;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.MethodSource;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlError;
import sabot.controlml.ControlMlIQ;
import sabot.controlml.ControlMlType;
import sabot.controlml.PresenceLevel;
import sabot.controlml.PresenceLevelElement;
import sabot.controlml.RequestId;
import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.internal.SchemaValidator;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.PayloadCodec;
import sabot.controlml.swe.SweComponent;

/** Serialising and parsing are symmetric for every resource, and what we write is valid against controlml.xsd. */
class ControlMlRoundTripTest {

    private static final RequestId ID = new RequestId(LocalDate.of(2026, 11, 21), 42);

    static Stream<Resource<?, ?>> resources() {
        return Resources.all().stream();
    }

    @ParameterizedTest
    @MethodSource("resources")
    void everyResourceValueSurvivesElementXmlAndCodecRoundTrip(Resource<?, ?> resource) throws Exception {
        Object value = Samples.VALUES.get(resource);
        assertNotNull(value, "no sample for " + resource);
        SweComponent payload = encode(resource, value);
        ControlMlType type = resource.isSettable() ? ControlMlType.SET : ControlMlType.RESULT;
        ControlMlElement sent = type == ControlMlType.SET ? ControlMlElement.request(type, ID, resource.name(), payload)
                : ControlMlElement.result(ID, resource.name(), payload);

        String xml = Xml.xml(sent);
        ControlMlElement received = Xml.element(xml);

        assertNull(received.defect(), () -> "defect " + received.defect() + " in " + xml);
        assertEquals(sent, received);
        assertEquals(xml, Xml.xml(received.withTextForm(true)), "serialising the parsed element gives the same XML");
        assertEquals(value, resource.codec().decode(received.payload()));
        assertNull(SchemaValidator.shared().problemWith(xml), xml);
    }

    @SuppressWarnings("unchecked")
    private static <T> SweComponent encode(Resource<T, ?> resource, Object value) {
        return ((PayloadCodec<T>) resource.codec()).encode((T) value);
    }

    /**
     * A robot's mission detail made from an exception's message (a stream error's, with its line end) is one line of
     * at most 256 characters, so that the robot can still answer cm.mission (it once answered not-acceptable).
     */
    @Test
    void aMissionDetailWithLineEndsOrTooLongIsMadeSendable() throws Exception {
        String reason = "XMPP connection lost while moving (StreamErrorException: system-shutdown You can read more\n"
                + "<stream:error><system-shutdown/></stream:error>)" + "x".repeat(400);
        MissionStatus m = new MissionStatus(MissionState.FAILED, false, 24, reason);
        assertEquals(MissionStatus.DETAIL_MAX, m.detail().length());
        assertTrue(m.detail().startsWith("XMPP connection lost while moving (StreamErrorException: system-shutdown "
                + "You can read more <stream:error>") && m.detail().endsWith("x…"), m.detail());
        SweComponent encoded = MissionStatus.CODEC.encode(m);
        assertEquals(m, MissionStatus.CODEC.decode(encoded), "the robot's own endpoint sends it, and it reads back");
        assertEquals("idle", new MissionStatus(MissionState.IDLE, false, 0, "idle").detail(), "a plain one as it is");
    }

    @Test
    void getWithQueryRoundTripsInsideAnIq() throws Exception {
        ControlMlIQ iq = new ControlMlIQ(ControlMlElement.request(ControlMlType.GET, ID, Resources.FS_READ.name(),
                Resources.FS_READ.queryCodec().encode(Samples.QUERY)));
        iq.setStanzaId("s1");
        iq.setTo(JidCreate.from("robot@sabot.local/onboard"));

        ControlMlIQ parsed = assertInstanceOf(ControlMlIQ.class, Xml.stanza(Xml.xml(iq)));

        assertEquals(IQ.Type.get, parsed.getType());
        assertEquals(iq.element(), parsed.element());
        assertEquals(Samples.QUERY, Resources.FS_READ.queryCodec().decode(parsed.element().payload()));
    }

    @Test
    void errorAnswerCarriesStanzaErrorConditionAndFailureBothWays() throws Exception {
        ControlMlError error = ControlMlError.of(ControlMlCondition.WRONG_UNIT, "x is in 's', expected 'm'");
        ControlMlIQ iq = new ControlMlIQ(ControlMlElement.error(ID, "cm.goal", error));
        iq.setStanzaId("s2");
        String xml = Xml.xml(iq);

        ControlMlIQ parsed = assertInstanceOf(ControlMlIQ.class, Xml.stanza(xml));

        assertEquals(IQ.Type.error, parsed.getType());
        assertEquals(StanzaError.Condition.not_acceptable, parsed.getError().getCondition());
        assertEquals(error, ControlMlError.fromStanzaError(parsed.getError()));
        assertEquals(error, parsed.element().failure());
        assertNull(parsed.element().defect());
        assertNull(SchemaValidator.shared().problemWith(Xml.xml(iq.element())));
    }

    /**
     * What the connection really writes: {@code XmlStringBuilder.write(Writer, XmlEnvironment)} with the stream's
     * environment (jabber:client, xml:lang en). Smack 4.4.8 drops the xmlns of a {@code setDescriptiveEnText} text
     * on this path (not in {@code toXML()}); ControlML's literal text keeps it, so the parsed stanza error has it.
     */
    @Test
    void errorTextKeepsItsNamespaceOnTheConnectionsWritePath() throws Exception {
        ControlMlError error = ControlMlError.of(ControlMlCondition.WRONG_UNIT, "x is in 's', expected 'm' <&>");
        ControlMlIQ iq = new ControlMlIQ(ControlMlElement.error(ID, "cm.goal", error));
        iq.setTo(JidCreate.from("wb@sabot.local/x"));
        iq.setStanzaId("s3");
        org.jivesoftware.smack.packet.XmlEnvironment stream = org.jivesoftware.smack.packet.XmlEnvironment.builder()
                .withNamespace("jabber:client").withLanguage("en").build();
        java.io.StringWriter wire = new java.io.StringWriter();
        iq.toXML(stream).write(wire, stream);
        String xml = wire.toString();
        assertTrue(xml.contains("<text xmlns='urn:ietf:params:xml:ns:xmpp-stanzas' xml:lang='en'>"), xml);

        // as received: the stream's default namespace around it
        ControlMlIQ parsed = assertInstanceOf(ControlMlIQ.class, Xml.stanza(xml.replaceFirst("<iq ",
                "<iq xmlns='jabber:client' ")));
        assertEquals(error.text(), parsed.getError().getDescriptiveText("en"), xml);
        assertEquals(error, ControlMlError.fromStanzaError(parsed.getError()));

        // a peer whose Smack wrote the text without its namespace is still understood
        String unqualified = xml.replace("<text xmlns='urn:ietf:params:xml:ns:xmpp-stanzas' xml:lang='en'>",
                "<text xml:lang='en'>").replaceFirst("<iq ", "<iq xmlns='jabber:client' ");
        IQ old = (IQ) Xml.stanza(unqualified);
        assertNull(old.getError().getDescriptiveText("en"), unqualified);
        assertEquals(error, ControlMlError.fromStanzaError(old.getError()));
    }

    @Test
    void aMissionStatusOutsideTheSchemasProgressRangeCannotBeMade() {
        // the robot's endpoint refuses to send such a status (the range of section 4): it must fail where it is made
        for (double progress : new double[] {-5.9e-4, 100.01, Double.NaN}) {
            IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                    () -> new MissionStatus(MissionState.RUNNING, false, progress, "to the dock"));
            assertTrue(e.getMessage().contains("outside [0, 100]"), e.getMessage());
        }
        assertEquals(100.0, new MissionStatus(MissionState.DONE, false, 100, "arrived").progress());
    }

    @Test
    void presenceLevelElementRoundTripsAndValidates() throws Exception {
        PresenceLevelElement e = new PresenceLevelElement(PresenceLevel.BUSY, "running", false);
        String xml = "<presence xmlns='jabber:client' from='r@sabot.local/x'><show>dnd</show>" + Xml.xml(e)
                + "</presence>";

        org.jivesoftware.smack.packet.Presence p = (org.jivesoftware.smack.packet.Presence) Xml.stanza(xml);

        assertEquals(e, PresenceLevelElement.from(p));
        assertEquals(PresenceLevel.BUSY, PresenceLevel.fromMode(p));
        assertNull(SchemaValidator.shared().problemWith(Xml.xml(e)));
    }

    @Test
    void telemetryItemWithMicrosecondTimeRoundTrips() throws Exception {
        ControlMlElement item = ControlMlElement.result(ID, "cm.position", Resources.POSITION.codec().encode(
                Samples.POSE));
        assertEquals(Samples.POSE, Resources.POSITION.codec().decode(Xml.element(Xml.xml(item)).payload()));
        assertTrue(Xml.xml(item).contains("2026-11-21T10:15:30.123456Z"));
    }

    @Test
    void alternativeUnitsOfTheRightDimensionAreConvertedToCanonical() throws Exception {
        String xml = "<control-ml xmlns='urn:sabot:controlml:1' type='set' id='20261121:7' res='cm.goal'>"
                + "<DataRecord xmlns='http://www.opengis.net/swe/2.0'>"
                + "<field name='x'><Quantity><uom code='cm'/><value>150</value></Quantity></field>"
                + "<field name='y'><Quantity><uom code='m'/><value>2</value></Quantity></field>"
                + "<field name='theta'><Quantity><uom code='deg'/><value>90</value></Quantity></field>"
                + "<field name='positionTolerance'><Quantity><uom code='mm'/><value>50</value></Quantity></field>"
                + "<field name='headingTolerance'><Quantity><uom code='rad'/><value>0.1</value></Quantity></field>"
                + "</DataRecord></control-ml>";

        var goal = Resources.GOAL.codec().decode(Xml.element(xml).payload());

        assertEquals(1.5, goal.pose().x(), 1e-12);
        assertEquals(Math.PI / 2, goal.pose().theta(), 1e-12);
        assertEquals(0.05, goal.positionTolerance(), 1e-12);
    }
}
