package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;

import java.io.StringReader;
import java.time.Clock;
import java.time.Instant;
import java.time.LocalDate;
import java.time.ZoneOffset;
import java.util.concurrent.atomic.AtomicInteger;

import javax.xml.parsers.DocumentBuilderFactory;

import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;
import org.w3c.dom.Attr;
import org.w3c.dom.NamedNodeMap;
import org.w3c.dom.Node;
import org.xml.sax.InputSource;

import sabot.controlml.Carrier;
import sabot.controlml.ControlMl;
import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlError;
import sabot.controlml.ControlMlType;
import sabot.controlml.Outcome;
import sabot.controlml.RequestId;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.internal.Endpoint;
import sabot.controlml.payload.Goal;

/**
 * The rules of docs/CONTROLML.md that an independent implementation found the device breaking (issue 14): the
 * order of checks, replay, numbers of any length, the payload size as defined in section 1 at its edge, and the
 * element counts section 3 quotes. Through the endpoint, without a server; the same cases over the wire are in
 * {@link ControlMlOnServerTest} and the slixmpp interop suite.
 */
class ConformanceTest {

    private static final String SET_GOAL = "<control-ml xmlns='urn:sabot:controlml:1' type='set' id='20261121:7' "
            + "res='cm.goal'" + ControlMlBadInputTest.SENT + ">";

    private Jid operator;
    private RecordingDevice device;
    private Endpoint endpoint;

    @BeforeEach
    void setUp() throws Exception {
        operator = JidCreate.from("operator@sabot.local/wb");
        device = new RecordingDevice();
        endpoint = RecordingDevice.endpoint(Clock.fixed(Instant.parse("2026-11-21T12:00:00Z"), ZoneOffset.UTC),
                device);
        endpoint.setAccessPolicy(j -> Role.MAINTAINER);
    }

    private Endpoint.Answer serve(String xml, ControlMlType carrierType) throws Exception {
        return endpoint.serve(Xml.element(xml), carrierType, operator, null, Carrier.IQ);
    }

    private static ControlMlError errorOf(Endpoint.Answer a) {
        if (a.element() == null) {
            return a.bareError();
        }
        return a.element().type() == ControlMlType.ERROR ? a.element().failure() : null;
    }

    private static String goalPayload(String x) {
        String goal = ControlMlBadInputTest.goal(x, "m");
        return goal.substring(goal.indexOf("<DataRecord"), goal.lastIndexOf("</control-ml>"));
    }

    // ------------------------------------------------------------------------------------------ order of checks

    @Test
    void anAnswerTypeInARequestCarrierIsATypeMismatchNotAMalformedPayload() throws Exception {
        String[] answers = {
            "<control-ml xmlns='urn:sabot:controlml:1' type='error' id='20261121:1' res='cm.goal'/>",
            "<control-ml xmlns='urn:sabot:controlml:1' type='result' id='20261121:2' res='cm.goal'><failure "
                    + "condition='bad-request' reason='bad-id'>x</failure></control-ml>",
            "<control-ml xmlns='urn:sabot:controlml:1' type='error' id='20261121:3' res='cm.goal'>"
                    + goalPayload("1") + "</control-ml>" };
        for (String xml : answers) {
            for (ControlMlType carrier : new ControlMlType[] { ControlMlType.GET, ControlMlType.SET }) {
                ControlMlError error = errorOf(serve(xml, carrier));
                assertNotNull(error, xml);
                assertEquals(ControlMlCondition.TYPE_MISMATCH, error.cmCondition(), xml + " in " + carrier);
            }
        }
        assertEquals(0, device.applied.size());
    }

    @Test
    void aRetransmittedSetIsAnsweredFromMemoryEvenWhenItArrivesMalformed() throws Exception {
        Endpoint.Answer first = serve(SET_GOAL + goalPayload("1.5") + "</control-ml>", ControlMlType.SET);
        assertEquals(ControlMlType.RESULT, first.element().type());
        Endpoint.Answer again = serve(SET_GOAL + "<DataRecord xmlns='http://www.opengis.net/swe/2.0'><field "
                + "name='x'><Oops/></field></DataRecord></control-ml>", ControlMlType.SET);
        assertEquals(first.element(), again.element(), "the remembered answer, not malformed-payload");
        assertEquals(1, device.applied.size());
        assertEquals(1, endpoint.duplicatesReplayed());
    }

    @Test
    void aDifferentCommandUnderAUsedIdGetsTheFirstAnswerAndIsNotApplied() throws Exception {
        serve(SET_GOAL + goalPayload("1.5") + "</control-ml>", ControlMlType.SET);
        Endpoint.Answer other = serve(SET_GOAL + goalPayload("4") + "</control-ml>", ControlMlType.SET);
        assertEquals(ControlMlType.RESULT, other.element().type());
        assertEquals(1.5, ((Goal) device.state.get("cm.goal")).pose().x());
        assertEquals(1, device.applied.size());
    }

    @Test
    void aBusyRefusalIsNotRememberedSoTheRetryIsTakenAsNew() throws Exception {
        AtomicInteger calls = new AtomicInteger();
        endpoint.onSet(Resources.GOAL, (r, g) -> calls.incrementAndGet() == 1 ? Outcome.failure(
                ControlMlCondition.BUSY, "queue full") : Outcome.done());
        String xml = SET_GOAL + goalPayload("1.5") + "</control-ml>";
        assertEquals(ControlMlCondition.BUSY, errorOf(serve(xml, ControlMlType.SET)).cmCondition());
        assertNull(errorOf(serve(xml, ControlMlType.SET)), "the retry later must be applied");
        assertEquals(2, calls.get());
        serve(xml, ControlMlType.SET);
        assertEquals(2, calls.get(), "the accepted retry is remembered");
    }

    @Test
    void theResourceIsCheckedBeforeThePayload() throws Exception {
        ControlMlError error = errorOf(serve("<control-ml xmlns='urn:sabot:controlml:1' type='set' id='20261121:4' "
                + "res='cm.teleport'><DataRecord xmlns='http://www.opengis.net/swe/2.0'><Oops/></DataRecord>"
                + "</control-ml>", ControlMlType.SET));
        assertEquals(ControlMlCondition.UNKNOWN_RESOURCE, error.cmCondition());
    }

    // ------------------------------------------------------------------------------------------ values

    @Test
    void anXsDoubleOfAnyLengthIsANumber() throws Exception {
        String x = "0." + "0".repeat(200) + "15e201";
        Endpoint.Answer a = serve(SET_GOAL + goalPayload(x) + "</control-ml>", ControlMlType.SET);
        assertNull(errorOf(a), () -> String.valueOf(errorOf(a)));
        assertEquals(1.5, ((Goal) device.state.get("cm.goal")).pose().x(), 1e-12);
    }

    // ------------------------------------------------------------------------------------------ payload size

    /**
     * ControlML's payload size (section 1), computed independently of the reader from a DOM: an element counts its
     * local name twice plus 5, an attribute that is not a namespace declaration its local name and value plus 4,
     * text its code points; comments nothing.
     */
    static int payloadSize(String payloadXml) throws Exception {
        DocumentBuilderFactory f = DocumentBuilderFactory.newInstance();
        f.setNamespaceAware(true);
        return size(f.newDocumentBuilder().parse(new InputSource(new StringReader(payloadXml))).getDocumentElement());
    }

    private static int size(Node n) {
        return switch (n.getNodeType()) {
            case Node.ELEMENT_NODE -> {
                String name = n.getLocalName();
                int s = 2 * cp(name) + 5;
                NamedNodeMap attributes = n.getAttributes();
                for (int i = 0; i < attributes.getLength(); i++) {
                    Attr a = (Attr) attributes.item(i);
                    if (!"http://www.w3.org/2000/xmlns/".equals(a.getNamespaceURI())) {
                        s += cp(a.getLocalName()) + cp(a.getValue()) + 4;
                    }
                }
                for (Node c = n.getFirstChild(); c != null; c = c.getNextSibling()) {
                    s += size(c);
                }
                yield s;
            }
            case Node.TEXT_NODE, Node.CDATA_SECTION_NODE -> cp(n.getNodeValue());
            default -> 0;
        };
    }

    private static int cp(String s) {
        return s.codePointCount(0, s.length());
    }

    /** A goal padded with white space between its elements (which counts) to exactly {@code size}. */
    private static String goalOfSize(int size) throws Exception {
        String payload = goalPayload("1.5");
        int pad = size - payloadSize(payload);
        int at = payload.indexOf("<field");
        String padded = payload.substring(0, at) + " \n\t".repeat(pad / 3) + " ".repeat(pad % 3) + payload.substring(
                at);
        assertEquals(size, payloadSize(padded));
        return padded;
    }

    @Test
    void aPayloadOfExactlyTheLimitIsAcceptedAndOneMoreIsTooLarge() throws Exception {
        Endpoint.Answer atLimit = serve(SET_GOAL + goalOfSize(ControlMl.MAX_PAYLOAD_CHARS) + "</control-ml>",
                ControlMlType.SET);
        assertNull(errorOf(atLimit), () -> String.valueOf(errorOf(atLimit)));
        ControlMlError over = errorOf(serve(SET_GOAL.replace(":7'", ":8'") + goalOfSize(ControlMl.MAX_PAYLOAD_CHARS
                + 1) + "</control-ml>", ControlMlType.SET));
        assertEquals(ControlMlCondition.PAYLOAD_TOO_LARGE, over.cmCondition(), over.toString());
        assertEquals(1, device.applied.size());
    }

    @Test
    void thePayloadSizeCountsCodePointsNotUtf16UnitsAndIgnoresNamespaceDeclarations() throws Exception {
        // a Text is not a goal (malformed-payload) but is read to its end first: the size decides the reason
        String head = "<Text xmlns='http://www.opengis.net/swe/2.0' xmlns:unused='urn:x'><value>";
        String tail = "</value></Text>";
        String emoji = new String(Character.toChars(0x1F600));
        int fixed = payloadSize(head + tail);
        int n = ControlMl.MAX_PAYLOAD_CHARS - fixed;
        String atLimit = head + emoji.repeat(n) + tail;
        assertEquals(ControlMl.MAX_PAYLOAD_CHARS, payloadSize(atLimit));
        assertEquals(ControlMlCondition.MALFORMED_PAYLOAD, errorOf(serve(SET_GOAL + atLimit + "</control-ml>",
                ControlMlType.SET)).cmCondition());
        assertEquals(ControlMlCondition.PAYLOAD_TOO_LARGE, errorOf(serve(SET_GOAL.replace(":7'", ":9'") + head
                + emoji.repeat(n + 1) + tail + "</control-ml>", ControlMlType.SET)).cmCondition());
    }

    @Test
    void aValueThatDoesNotFitOnePayloadIsRefusedNotSent() throws Exception {
        byte[] cells = new byte[200 * 200]; // "0" and a separator per cell: 80,000 > 65,536
        endpoint.onGet(Resources.MAP, (r, q) -> Outcome.success(new sabot.controlml.payload.GridMap(0.05, 200, 200,
                new sabot.model.geometry.Pose2D(0, 0, 0), cells)));
        ControlMlError error = errorOf(serve("<control-ml xmlns='urn:sabot:controlml:1' type='get' id='20261121:5' "
                + "res='cm.map'/>", ControlMlType.GET));
        assertNotNull(error);
        assertEquals(ControlMlCondition.PAYLOAD_TOO_LARGE, error.cmCondition(), error.toString());
        assertNull(errorOf(serve("<control-ml xmlns='urn:sabot:controlml:1' type='get' id='20261121:6' "
                + "res='cm.position'/>", ControlMlType.GET)), "a small answer still goes out");
    }

    // ------------------------------------------------------------------------------------------ section 3's figures

    private static int elements(String xml) throws Exception {
        DocumentBuilderFactory f = DocumentBuilderFactory.newInstance();
        f.setNamespaceAware(true);
        return f.newDocumentBuilder().parse(new InputSource(new StringReader(xml))).getElementsByTagName("*")
                .getLength();
    }

    @Test
    void aPoseHas45PayloadElementsInTheXmlFormAnd5InTheTextForm() throws Exception {
        ControlMlElement pose = ControlMlElement.result(new RequestId(LocalDate.of(2026, 11, 21), 7),
                Resources.POSITION.name(), Resources.POSITION.codec().encode(Samples.POSE));
        assertEquals(45, elements(pose.withTextForm(false).contentXml()));
        assertEquals(5, elements(pose.withTextForm(true).contentXml()));
    }
}
