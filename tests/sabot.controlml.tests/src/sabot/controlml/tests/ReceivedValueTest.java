package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.Map;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlType;
import sabot.controlml.RequestId;
import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.PayloadCodec;
import sabot.controlml.payload.PayloadException;
import sabot.controlml.payload.PoseEstimate;
import sabot.controlml.swe.Count;
import sabot.controlml.swe.DataRecord;

/**
 * {@link ControlMlElement#value}: a received result's payload is decoded while it is read (on the connection's reader
 * thread), with exactly the codec's outcome — the value, or the same refusal.
 */
class ReceivedValueTest {

    private static final RequestId ID = RequestId.parse("20261121:7");
    private static final String POSITION_RESULT = "<control-ml xmlns='urn:sabot:controlml:1' type='result' "
            + "id='20261121:7' res='cm.position'><DataStream xmlns='http://www.opengis.net/swe/2.0' "
            + "xmlns:xlink='http://www.w3.org/1999/xlink'><elementType name='value' "
            + "xlink:href='urn:sabot:controlml:1:record:cm.position'/><encoding><TextEncoding tokenSeparator=',' "
            + "blockSeparator=' '/></encoding><values>2026-11-21T10:15:30Z,1.25,-3.5,0.785,%s</values></DataStream>"
            + "</control-ml>";

    @Test
    void everyResourcesResultIsDecodedAsItsCodecDecodesIt() throws Exception {
        for (Map.Entry<Resource<?, ?>, Object> sample : Samples.VALUES.entrySet()) {
            Resource<?, ?> resource = sample.getKey();
            for (boolean text : new boolean[] { true, false }) {
                ControlMlElement sent = ControlMlElement.result(ID, resource.name(), encode(resource, sample
                        .getValue())).withTextForm(text);
                ControlMlElement received = Xml.element(Xml.xml(sent));
                assertEquals(sample.getValue(), received.value(resource), resource.name() + (text ? " text" : " xml"));
                assertEquals(resource.codec().decode(received.payload()), received.value(resource));
            }
        }
    }

    @Test
    void aResultTheCodecRefusesIsRefusedTheSameWayEachTime() throws Exception {
        ControlMlElement received = Xml.element(String.format(POSITION_RESULT, "-0.01,0,0,0.02,0,0.03"));
        assertNull(received.defect(), "the structure is fine; the value is what is wrong");
        PayloadException expected = assertThrows(PayloadException.class, () -> Resources.POSITION.codec().decode(
                received.payload()));
        for (int i = 0; i < 2; i++) {
            PayloadException e = assertThrows(PayloadException.class, () -> received.value(Resources.POSITION));
            assertEquals(ControlMlCondition.INVALID_VALUE, e.error().cmCondition());
            assertEquals(expected.getMessage(), e.getMessage());
        }
    }

    /** The field's path in a message is built only when there is one to write, and still names the array cell. */
    @Test
    void aNonFiniteCovarianceCellIsNamedByItsPath() throws Exception {
        ControlMlElement received = Xml.element(String.format(POSITION_RESULT, "0.01,NaN,0,0.02,0,0.03"));
        PayloadException e = assertThrows(PayloadException.class, () -> received.value(Resources.POSITION));
        assertEquals(ControlMlCondition.INVALID_VALUE, e.error().cmCondition());
        assertTrue(e.getMessage().startsWith("covariance[0].xy must be finite"), e.getMessage());
    }

    @Test
    void anotherResourceDecodesTheSamePayloadWithItsOwnCodec() throws Exception {
        ControlMlElement received = Xml.element(String.format(POSITION_RESULT, "0.01,0,0,0.02,0,0.03"));
        PoseEstimate pose = received.value(Resources.POSITION);
        assertEquals(1.25, pose.pose().x());
        PayloadException e = assertThrows(PayloadException.class, () -> received.value(Resources.GOAL));
        assertEquals(ControlMlCondition.MALFORMED_PAYLOAD, e.error().cmCondition());
    }

    @Test
    void requestsAreDecodedWhenAsked() throws Exception {
        Goal goal = (Goal) Samples.VALUES.get(Resources.GOAL);
        ControlMlElement sent = ControlMlElement.request(ControlMlType.SET, ID, Resources.GOAL.name(), Resources.GOAL
                .codec().encode(goal));
        ControlMlElement received = Xml.element(Xml.xml(sent));
        assertEquals(goal, received.value(Resources.GOAL));
    }

    @Test
    void anElementWithoutPayloadHasNoValue() throws Exception {
        ControlMlElement received = Xml.element(Xml.xml(ControlMlElement.result(ID, "cm.goal", null)));
        assertThrows(IllegalStateException.class, () -> received.value(Resources.GOAL));
    }

    @Test
    void contentIsWrittenOnce() {
        ControlMlElement e = ControlMlElement.result(ID, Resources.POSITION.name(), Resources.POSITION.codec().encode(
                Samples.POSE));
        assertSame(e.contentXml(), e.contentXml());
    }

    @ParameterizedTest
    @ValueSource(strings = { "cm.position", "cm.fs.read", "cm.not-in-the-catalogue", "cm.a.b.c.d" })
    void resourceNames(String res) {
        assertTrue(ControlMlElement.isResourceName(res));
    }

    @ParameterizedTest
    @ValueSource(strings = { "", "cm", "cm.", "CM.position", "cm.Position", "cm.a.b.c.d.e", "x.position",
        "cm.position " })
    void notResourceNames(String res) {
        assertFalse(ControlMlElement.isResourceName(res));
    }

    @Test
    void nullIsNoResourceName() {
        assertFalse(ControlMlElement.isResourceName(null));
    }

    @ParameterizedTest
    @ValueSource(ints = { 2, 16, 17, 40 })
    void duplicateFieldNamesAreRefused(int fields) {
        java.util.List<DataRecord.Field> list = new java.util.ArrayList<>();
        for (int i = 0; i < fields - 1; i++) {
            list.add(new DataRecord.Field("f" + i, new Count(i)));
        }
        list.add(new DataRecord.Field("f" + (fields - 1) / 2, new Count(-1)));
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> new DataRecord(list));
        assertEquals("duplicate field name f" + (fields - 1) / 2, e.getMessage());
        list.set(fields - 1, new DataRecord.Field("g", new Count(-1)));
        assertEquals(fields, new DataRecord(list).fields().size());
    }

    @Test
    void aReceivedRecordWithTwoFieldsOfOneNameIsMalformed() throws Exception {
        String quantity = "<Quantity><uom code='m'/><value>1</value></Quantity>";
        ControlMlElement received = Xml.element("<control-ml xmlns='urn:sabot:controlml:1' type='result' "
                + "id='20261121:7' res='cm.goal'><DataRecord xmlns='http://www.opengis.net/swe/2.0'><field name='x'>"
                + quantity + "</field><field name='x'>" + quantity + "</field></DataRecord></control-ml>");
        assertEquals(ControlMlCondition.MALFORMED_PAYLOAD, received.defect().cmCondition());
    }

    @SuppressWarnings("unchecked")
    private static <T> sabot.controlml.swe.SweComponent encode(Resource<T, ?> resource, Object value) {
        return ((PayloadCodec<T>) resource.codec()).encode((T) value);
    }
}
