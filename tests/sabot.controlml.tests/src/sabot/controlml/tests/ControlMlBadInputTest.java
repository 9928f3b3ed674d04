package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Clock;
import java.time.Duration;
import java.time.Instant;
import java.time.ZoneOffset;
import java.util.HashMap;
import java.util.Map;

import org.jivesoftware.smack.packet.StanzaError.Condition;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.Carrier;
import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlError;
import sabot.controlml.ControlMlType;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.StaleCommandPolicy;
import sabot.controlml.internal.Endpoint;
import sabot.controlml.payload.Goal;
import sabot.model.geometry.Pose2D;

/**
 * Every kind of bad input gets the right error, the device's state stays as it was, and nothing throws. (The same
 * checks run over a real connection in {@link ControlMlOnServerTest}.)
 */
class ControlMlBadInputTest {

    /** The send time of the sets below: the device's (fixed) clock, so they are fresh (section 5). */
    static final String SENT = " sent='2026-11-21T12:00:00Z'";
    static final String HEAD = "<control-ml xmlns='urn:sabot:controlml:1' type='set' id='20261121:7' res='cm.goal'"
            + SENT + ">";
    static final String SWE = "<DataRecord xmlns='http://www.opengis.net/swe/2.0'>";

    static String goal(String x, String xUnit) {
        return HEAD + SWE + "<field name='x'><Quantity><uom code='" + xUnit + "'/><value>" + x
                + "</value></Quantity></field>"
                + "<field name='y'><Quantity><uom code='m'/><value>2</value></Quantity></field>"
                + "<field name='theta'><Quantity><uom code='rad'/><value>0</value></Quantity></field>"
                + "<field name='positionTolerance'><Quantity><uom code='m'/><value>0.05</value></Quantity></field>"
                + "<field name='headingTolerance'><Quantity><uom code='rad'/><value>0.1</value></Quantity></field>"
                + "</DataRecord></control-ml>";
    }

    private final Instant now = Instant.parse("2026-11-21T12:00:00Z");
    private Jid operator;
    private RecordingDevice device;
    private Endpoint endpoint;
    private final Map<Jid, Role> access = new HashMap<>();

    @BeforeEach
    void setUp() throws Exception {
        operator = JidCreate.from("operator@sabot.local/wb");
        device = new RecordingDevice();
        endpoint = RecordingDevice.endpoint(Clock.fixed(now, ZoneOffset.UTC), device);
        access.put(operator, Role.MAINTAINER);
        access.put(JidCreate.from("viewer@sabot.local/wb"), Role.OBSERVER);
        endpoint.setAccessPolicy(j -> access.getOrDefault(j, Role.NONE));
    }

    private Endpoint.Answer serve(String xml) throws Exception {
        return serve(xml, operator, null);
    }

    private Endpoint.Answer serve(String xml, Jid from, Instant delay) throws Exception {
        ControlMlElement e = Xml.element(xml);
        return endpoint.serve(e, e.type() == null ? ControlMlType.SET : e.type(), from, delay, Carrier.IQ);
    }

    private static ControlMlError errorOf(Endpoint.Answer a) {
        if (a.element() == null) {
            return a.bareError();
        }
        assertEquals(ControlMlType.ERROR, a.element().type(), "expected an error, got " + a.element());
        return a.element().failure();
    }

    private void assertRefused(Endpoint.Answer a, Condition condition, ControlMlCondition cm) {
        ControlMlError error = errorOf(a);
        assertNotNull(error);
        assertEquals(condition, error.condition(), error.toString());
        assertEquals(cm, error.cmCondition(), error.toString());
        assertTrue(device.applied.isEmpty(), "state changed: " + device.applied);
        assertEquals(Samples.VALUES.get(Resources.GOAL), device.state.get("cm.goal"));
    }

    @Test
    void aValidSetIsAppliedOnce() throws Exception {
        Endpoint.Answer a = serve(goal("1.5", "m"));
        assertEquals(ControlMlType.RESULT, a.element().type());
        assertEquals(1, device.applied.size());
    }

    @ParameterizedTest(name = "{0}")
    @CsvSource(delimiter = '|', value = {
        "NaN is refused | NaN | m | NOT_ACCEPTABLE | INVALID_VALUE",
        "INF is refused | INF | m | NOT_ACCEPTABLE | INVALID_VALUE",
        "-INF is refused | -INF | m | NOT_ACCEPTABLE | INVALID_VALUE",
        "seconds for a length | 1 | s | NOT_ACCEPTABLE | WRONG_UNIT",
        "unknown unit | 1 | furlong | NOT_ACCEPTABLE | WRONG_UNIT",
        "hexadecimal float | 0x1p3 | m | BAD_REQUEST | MALFORMED_PAYLOAD",
        "decimal comma | 1,5 | m | BAD_REQUEST | MALFORMED_PAYLOAD",
        "Java's Infinity | Infinity | m | BAD_REQUEST | MALFORMED_PAYLOAD",
        "empty value | '' | m | BAD_REQUEST | MALFORMED_PAYLOAD" })
    void badQuantitiesAreRefused(String why, String value, String unit, String condition, String cm) throws Exception {
        assertRefused(serve(goal(value, unit)), Condition.valueOf(condition.toLowerCase().replace('-', '_')),
                ControlMlCondition.valueOf(cm));
    }

    /** A cm.position set whose covariance is the compact DataArray row, with the given parts. */
    static String position(String elementCount, String xyUnit, String values) {
        return "<control-ml xmlns='urn:sabot:controlml:1' type='set' id='20261121:8' res='cm.position'>" + SWE
                + "<field name='time'><Time><uom xmlns:xlink='http://www.w3.org/1999/xlink' xlink:href="
                + "'http://www.opengis.net/def/uom/ISO-8601/0/Gregorian'/><value>2026-11-21T11:59:59Z</value></Time>"
                + "</field><field name='x'><Quantity><uom code='m'/><value>1</value></Quantity></field>"
                + "<field name='y'><Quantity><uom code='m'/><value>2</value></Quantity></field>"
                + "<field name='theta'><Quantity><uom code='rad'/><value>0</value></Quantity></field>"
                + "<field name='covariance'><DataArray><elementCount><Count><value>" + elementCount
                + "</value></Count></elementCount><elementType name='covariance'><DataRecord>"
                + "<field name='xx'><Quantity><uom code='m2'/></Quantity></field>"
                + "<field name='xy'><Quantity><uom code='" + xyUnit + "'/></Quantity></field>"
                + "<field name='xtheta'><Quantity><uom code='m.rad'/></Quantity></field>"
                + "<field name='yy'><Quantity><uom code='m2'/></Quantity></field>"
                + "<field name='ytheta'><Quantity><uom code='m.rad'/></Quantity></field>"
                + "<field name='thetatheta'><Quantity><uom code='rad2'/></Quantity></field>"
                + "</DataRecord></elementType><encoding><TextEncoding tokenSeparator=',' blockSeparator=' '/>"
                + "</encoding><values>" + values + "</values></DataArray></field></DataRecord></control-ml>";
    }

    @Test
    void aCompactCovarianceIsAccepted() throws Exception {
        Endpoint.Answer a = serve(position("1", "m2", "0.01,0.001,0,0.02,0,0.003"));
        assertEquals(ControlMlType.RESULT, a.element().type(), String.valueOf(a.element()));
        assertEquals(1, device.applied.size());
        sabot.controlml.payload.PoseEstimate p = (sabot.controlml.payload.PoseEstimate) device.state.get(
                "cm.position");
        assertEquals(new sabot.controlml.payload.PoseCovariance(0.01, 0.001, 0, 0.02, 0, 0.003), p.covariance());
    }

    @ParameterizedTest(name = "{0}")
    @CsvSource(delimiter = '|', value = {
        "NaN in the covariance | 1 | m2 | 0.01,NaN,0,0.02,0,0.003 | NOT_ACCEPTABLE | INVALID_VALUE",
        "INF in the covariance | 1 | m2 | 0.01,0,INF,0.02,0,0.003 | NOT_ACCEPTABLE | INVALID_VALUE",
        "-INF in the covariance | 1 | m2 | 0.01,0,0,0.02,0,-INF | NOT_ACCEPTABLE | INVALID_VALUE",
        "negative variance | 1 | m2 | 0.01,0,0,-0.02,0,0.003 | NOT_ACCEPTABLE | INVALID_VALUE",
        "wrong unit (time for area) | 1 | s2 | 0.01,0,0,0.02,0,0.003 | NOT_ACCEPTABLE | WRONG_UNIT",
        "unknown unit | 1 | furlong2 | 0.01,0,0,0.02,0,0.003 | NOT_ACCEPTABLE | WRONG_UNIT",
        "elementCount does not match the values | 2 | m2 | 0.01,0,0,0.02,0,0.003 | BAD_REQUEST | MALFORMED_PAYLOAD",
        "two rows | 2 | m2 | 0.01,0,0,0.02,0,0.003 0.01,0,0,0.02,0,0.003 | BAD_REQUEST | MALFORMED_PAYLOAD",
        "no row | 0 | m2 | '' | BAD_REQUEST | MALFORMED_PAYLOAD",
        "five values in the row | 1 | m2 | 0.01,0,0,0.02,0 | BAD_REQUEST | MALFORMED_PAYLOAD",
        "seven values in the row | 1 | m2 | 0.01,0,0,0.02,0,0.003,1 | BAD_REQUEST | MALFORMED_PAYLOAD",
        "decimal comma | 1 | m2 | 0.01;0,0,0,0.02,0,0.003 | BAD_REQUEST | MALFORMED_PAYLOAD",
        "Java's Infinity | 1 | m2 | 0.01,0,Infinity,0.02,0,0.003 | BAD_REQUEST | MALFORMED_PAYLOAD" })
    void badCovariancesAreRefused(String why, String count, String xyUnit, String values, String condition,
            String cm) throws Exception {
        Endpoint.Answer a = serve(position(count, xyUnit, values));
        ControlMlError error = errorOf(a);
        assertNotNull(error, why);
        assertEquals(Condition.valueOf(condition.toLowerCase()), error.condition(), why + ": " + error);
        assertEquals(ControlMlCondition.valueOf(cm), error.cmCondition(), why + ": " + error);
        assertTrue(device.applied.isEmpty(), "state changed: " + device.applied);
    }

    /** A cm.goal set in the text form (docs/CONTROLML.md section 3) with the given parts. */
    static String goalStream(String elementType, String encoding, String values) {
        return HEAD + "<DataStream xmlns='http://www.opengis.net/swe/2.0' xmlns:xlink='http://www.w3.org/1999/xlink'>"
                + elementType + encoding + "<values>" + values + "</values></DataStream></control-ml>";
    }

    static final String GOAL_TYPE = "<elementType name='value' xlink:href='urn:sabot:controlml:1:record:cm.goal'/>";
    static final String TEXT_ENCODING = "<encoding><TextEncoding tokenSeparator=',' blockSeparator=' '/></encoding>";

    @Test
    void aTextFormSetIsApplied() throws Exception {
        Endpoint.Answer a = serve(goalStream(GOAL_TYPE, TEXT_ENCODING, "1.5,-2,0.25,0.05,0.1"));

        assertEquals(ControlMlType.RESULT, a.element().type(), () -> String.valueOf(a.element()));
        assertEquals(new Goal(new Pose2D(1.5, -2, 0.25), 0.05, 0.1), device.state.get("cm.goal"));
    }

    @ParameterizedTest(name = "{0}")
    @CsvSource(delimiter = '|', quoteCharacter = '"', value = {
        "too few values | | | 1,2,0,0.05 | MALFORMED_PAYLOAD",
        "too many values | | | 1,2,0,0.05,0.1,7 | MALFORMED_PAYLOAD",
        "two blocks | | | 1,2,0,0.05,0.1 1,2,0,0.05,0.1 | MALFORMED_PAYLOAD",
        "empty values | | | '' | MALFORMED_PAYLOAD",
        "decimal comma | | | 1;5,2,0,0.05,0.1 | MALFORMED_PAYLOAD",
        "hexadecimal number | | | 0x1p3,2,0,0.05,0.1 | MALFORMED_PAYLOAD",
        "NaN is parsed then refused | | | NaN,2,0,0.05,0.1 | INVALID_VALUE",
        "INF is parsed then refused | | | 1,INF,0,0.05,0.1 | INVALID_VALUE",
        "out of range tolerance | | | 1,2,0,-0.05,0.1 | INVALID_VALUE",
        "structure of another resource | <elementType name='value' xlink:href='urn:sabot:controlml:1:record:cm.position'/> | | 1,2,0,0.05,0.1 | MALFORMED_PAYLOAD",
        "unknown structure | <elementType name='value' xlink:href='urn:example:goal'/> | | 1,2,0,0.05,0.1 | MALFORMED_PAYLOAD",
        "elementType without name | <elementType xlink:href='urn:sabot:controlml:1:record:cm.goal'/> | | 1,2,0,0.05,0.1 | MALFORMED_PAYLOAD",
        "elementType without href | <elementType name='value'/> | | 1,2,0,0.05,0.1 | MALFORMED_PAYLOAD",
        "inline elementType content | <elementType name='value' xlink:href='urn:sabot:controlml:1:record:cm.goal'><Count/></elementType> | | 1,2,0,0.05,0.1 | MALFORMED_PAYLOAD",
        "other token separator | | <encoding><TextEncoding tokenSeparator=';' blockSeparator=' '/></encoding> | 1;2;0;0.05;0.1 | MALFORMED_PAYLOAD",
        "no encoding | | <encoding/> | 1,2,0,0.05,0.1 | MALFORMED_PAYLOAD",
        "element count | <elementCount><Count><value>1</value></Count></elementCount> | | 1,2,0,0.05,0.1 | MALFORMED_PAYLOAD" })
    void badTextFormsAreRefused(String why, String elementType, String encoding, String values, String cm)
            throws Exception {
        String xml = goalStream(elementType == null ? GOAL_TYPE : elementType, encoding == null ? TEXT_ENCODING
                : encoding, values == null ? "" : values);
        ControlMlCondition condition = ControlMlCondition.valueOf(cm);
        assertRefused(serve(xml), condition == ControlMlCondition.INVALID_VALUE ? Condition.not_acceptable
                : Condition.bad_request, condition);
    }

    @Test
    void aTextFormForAResourceWithoutRecordStructureIsRefused() throws Exception {
        String xml = HEAD.replace("cm.goal", "cm.trajectory") + "<DataStream xmlns='http://www.opengis.net/swe/2.0' "
                + "xmlns:xlink='http://www.w3.org/1999/xlink'><elementType name='value' "
                + "xlink:href='urn:sabot:controlml:1:record:cm.trajectory'/>" + TEXT_ENCODING
                + "<values>0,0,0,0,0,0</values></DataStream></control-ml>";
        assertRefused(serve(xml), Condition.bad_request, ControlMlCondition.MALFORMED_PAYLOAD);
    }

    @ParameterizedTest(name = "{0}")
    @CsvSource(delimiter = '|', value = {
        "unknown element | <bogus xmlns='urn:x'/> | BAD_REQUEST | MALFORMED_PAYLOAD",
        "text instead of payload | hello | BAD_REQUEST | MALFORMED_PAYLOAD",
        "two payloads | <Count xmlns='http://www.opengis.net/swe/2.0'><value>1</value></Count><Count xmlns='http://www.opengis.net/swe/2.0'><value>1</value></Count> | BAD_REQUEST | MALFORMED_PAYLOAD",
        "record missing fields | <DataRecord xmlns='http://www.opengis.net/swe/2.0'><field name='x'><Quantity><uom code='m'/><value>1</value></Quantity></field></DataRecord> | BAD_REQUEST | MALFORMED_PAYLOAD",
        "quantity without uom | <DataRecord xmlns='http://www.opengis.net/swe/2.0'><field name='x'><Quantity><value>1</value></Quantity></field></DataRecord> | BAD_REQUEST | MALFORMED_PAYLOAD",
        "unsupported SWE component | <Vector xmlns='http://www.opengis.net/swe/2.0'/> | BAD_REQUEST | MALFORMED_PAYLOAD",
        "failure in a set | <failure condition='bad-request' reason='bad-id'/> | BAD_REQUEST | MALFORMED_PAYLOAD" })
    void malformedContentIsRefused(String why, String content, String condition, String cm) throws Exception {
        assertRefused(serve(HEAD + content + "</control-ml>"), Condition.valueOf(condition.toLowerCase()),
                ControlMlCondition.valueOf(cm));
    }

    @ParameterizedTest(name = "{0}")
    @CsvSource(delimiter = '|', value = {
        "missing id | type='set' res='cm.goal' | BAD_ATTRIBUTES",
        "missing res | type='set' id='20261121:1' | BAD_ATTRIBUTES",
        "missing type | id='20261121:1' res='cm.goal' | BAD_ATTRIBUTES",
        "extra attribute | type='set' id='20261121:1' res='cm.goal' speed='fast' | BAD_ATTRIBUTES",
        "namespaced extra attribute | type='set' id='20261121:1' res='cm.goal' xml:lang='en' | BAD_ATTRIBUTES",
        "unknown type | type='put' id='20261121:1' res='cm.goal' | BAD_ATTRIBUTES",
        "id with dashes | type='set' id='2026-11-21:1' res='cm.goal' | BAD_ID",
        "id counter over UINT32 | type='set' id='20261121:4294967296' res='cm.goal' | BAD_ID",
        "id with impossible date | type='set' id='20260230:1' res='cm.goal' | BAD_ID",
        "res with upper case | type='set' id='20261121:1' res='CM.Goal' | BAD_ATTRIBUTES" })
    void badAttributesAreRefusedWithBadRequest(String why, String attributes, String cm) throws Exception {
        assertRefused(serve("<control-ml xmlns='urn:sabot:controlml:1' " + attributes + "/>"), Condition.bad_request,
                ControlMlCondition.valueOf(cm));
    }

    @Test
    void unknownResourceIsItemNotFound() throws Exception {
        assertRefused(serve(goal("1", "m").replace("cm.goal", "cm.teleport")), Condition.item_not_found,
                ControlMlCondition.UNKNOWN_RESOURCE);
    }

    @Test
    void payloadOver64KiBIsRefusedWhileReading() throws Exception {
        StringBuilder big = new StringBuilder(HEAD).append("<Text xmlns='http://www.opengis.net/swe/2.0'><value>");
        big.append("x".repeat(70_000)).append("</value></Text></control-ml>");
        assertRefused(serve(big.toString()), Condition.not_acceptable, ControlMlCondition.PAYLOAD_TOO_LARGE);
    }

    @Test
    void setOnAGetOnlyResourceIsServiceUnavailable() throws Exception {
        assertRefused(serve(HEAD.replace("cm.goal", "cm.tasks") + "<DataRecord xmlns='http://www.opengis.net/swe/2.0'>"
                + "<field name='count'><Count><value>0</value></Count></field></DataRecord></control-ml>"),
                Condition.service_unavailable, ControlMlCondition.UNSUPPORTED_OPERATION);
    }

    @Test
    void setWithoutPayloadIsBadRequest() throws Exception {
        assertRefused(serve("<control-ml xmlns='urn:sabot:controlml:1' type='set' id='20261121:1' res='cm.goal'/>"),
                Condition.bad_request, ControlMlCondition.PAYLOAD_MISMATCH);
    }

    @Test
    void setInsideAGetIqIsATypeMismatch() throws Exception {
        ControlMlElement e = Xml.element(goal("1", "m"));
        assertRefused(endpoint.serve(e, ControlMlType.GET, operator, null, Carrier.IQ), Condition.bad_request,
                ControlMlCondition.TYPE_MISMATCH);
    }

    @Test
    void unsolicitedResultInARequestPositionIsATypeMismatch() throws Exception {
        ControlMlElement e = Xml.element(goal("1", "m").replace("type='set'", "type='result'").replace(SENT, ""));
        assertRefused(endpoint.serve(e, ControlMlType.SET, operator, null, Carrier.IQ), Condition.bad_request,
                ControlMlCondition.TYPE_MISMATCH);
    }

    @Test
    void readOnlyRequesterMayGetButNotSet() throws Exception {
        Jid viewer = JidCreate.from("viewer@sabot.local/wb");
        assertRefused(serve(goal("1", "m"), viewer, null), Condition.forbidden, ControlMlCondition.SET_NOT_PERMITTED);
        ControlMlElement get = Xml.element("<control-ml xmlns='urn:sabot:controlml:1' type='get' id='20261121:2' "
                + "res='cm.goal'/>");
        assertEquals(ControlMlType.RESULT, endpoint.serve(get, ControlMlType.GET, viewer, null, Carrier.IQ).element()
                .type());
    }

    @Test
    void strangerIsForbiddenEvenToGet() throws Exception {
        ControlMlElement get = Xml.element("<control-ml xmlns='urn:sabot:controlml:1' type='get' id='20261121:2' "
                + "res='cm.goal'/>");
        assertRefused(endpoint.serve(get, ControlMlType.GET, JidCreate.from("mallory@evil.example/x"), null,
                Carrier.IQ), Condition.forbidden, ControlMlCondition.ACCESS_DENIED);
    }

    @Test
    void staleCommandIsRefusedAndFreshDelayedCommandApplied() throws Exception {
        endpoint.setStaleCommandPolicy(StaleCommandPolicy.refuseOlderThan(Duration.ofSeconds(30)));
        assertRefused(serve(goal("1", "m"), operator, now.minusSeconds(31)), Condition.not_acceptable,
                ControlMlCondition.STALE_COMMAND);
        Endpoint.Answer fresh = serve(goal("1", "m").replace(":7'", ":8'"), operator, now.minusSeconds(29));
        assertEquals(ControlMlType.RESULT, fresh.element().type());
    }

    @Test
    void retransmittedSetIsAnsweredAgainButAppliedOnce() throws Exception {
        Endpoint.Answer first = serve(goal("1", "m"));
        Endpoint.Answer again = serve(goal("1", "m"));
        assertEquals(first.element(), again.element());
        assertEquals(1, device.applied.size());
        assertEquals(1, endpoint.duplicatesReplayed());
    }

    @Test
    void failingHandlerIsADeviceFaultNotAnException() throws Exception {
        endpoint.onSet(Resources.GOAL, (r, g) -> {
            throw new IllegalStateException("motor driver on fire");
        });
        ControlMlError e = errorOf(serve(goal("1", "m")));
        assertEquals(ControlMlCondition.DEVICE_FAULT, e.cmCondition());
        assertTrue(e.text().contains("motor driver on fire"));
    }

    @Test
    void handlerErrorsTravelAsTheyAre() throws Exception {
        endpoint.onSet(Resources.GOAL, (r, g) -> Outcome.failure(ControlMlCondition.INVALID_STATE,
                "a mission is running"));
        ControlMlError e = errorOf(serve(goal("1", "m")));
        assertEquals(Condition.unexpected_request, e.condition());
        assertEquals("a mission is running", e.text());
    }

    @Test
    void getOfAResourceTheDeviceDoesNotServeIsServiceUnavailable() throws Exception {
        endpoint.removeHandlers(Resources.MAP);
        ControlMlElement get = Xml.element("<control-ml xmlns='urn:sabot:controlml:1' type='get' id='20261121:2' "
                + "res='cm.map'/>");
        ControlMlError e = errorOf(endpoint.serve(get, ControlMlType.GET, operator, null, Carrier.IQ));
        assertEquals(ControlMlCondition.UNSUPPORTED_OPERATION, e.cmCondition());
        assertNull(device.state.get("nothing"));
    }
}
