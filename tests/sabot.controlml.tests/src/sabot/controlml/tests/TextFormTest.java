package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Instant;
import java.time.LocalDate;
import java.util.List;
import java.util.stream.Stream;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.MethodSource;

import sabot.controlml.ControlMlElement;
import sabot.controlml.ControlMlType;
import sabot.controlml.RequestId;
import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.internal.SchemaValidator;
import sabot.controlml.payload.PayloadCodec;
import sabot.controlml.swe.DataArray;
import sabot.controlml.swe.DataRecord;
import sabot.controlml.swe.Quantity;
import sabot.controlml.swe.RecordTemplate;
import sabot.controlml.swe.SweBoolean;
import sabot.controlml.swe.SweComponent;
import sabot.controlml.swe.SweFormatException;
import sabot.controlml.swe.Text;
import sabot.controlml.swe.Time;

/**
 * The text form of a payload (docs/CONTROLML.md section 3): a SWE DataStream of one record whose structure is given by
 * reference. Written for the resources that have a record structure, read back to exactly what the XML form gives,
 * valid against controlml.xsd, and not used where a value does not fit.
 */
class TextFormTest {

    private static final RequestId ID = new RequestId(LocalDate.of(2026, 11, 21), 43);

    static Stream<Resource<?, ?>> structured() {
        return Resources.all().stream().filter(r -> r.recordTemplate() != null);
    }

    static Stream<Resource<?, ?>> unstructured() {
        return Resources.all().stream().filter(r -> r.recordTemplate() == null);
    }

    @Test
    void theFixedRecordsHaveAStructure() {
        assertEquals(List.of("cm.position", "cm.velocity", "cm.goal", "cm.limits"), structured().map(Resource::name)
                .toList());
    }

    @ParameterizedTest
    @MethodSource("structured")
    void aRecordTravelsAsOneBlockAndReadsBackAsTheXmlFormWould(Resource<?, ?> resource) throws Exception {
        SweComponent payload = encode(resource, Samples.VALUES.get(resource));
        ControlMlElement element = ControlMlElement.result(ID, resource.name(), payload);
        String text = Xml.xml(element);
        String xml = Xml.xml(element.withTextForm(false));

        assertTrue(text.contains("<DataStream ") && !text.contains("<DataRecord") && !text.contains("<field"), text);
        assertTrue(text.contains("xlink:href='urn:sabot:controlml:1:record:" + resource.name() + "'"), text);
        // what servers pay for: elements (control-ml, DataStream, elementType, encoding, TextEncoding, values)
        assertEquals(6, elements(text), text);
        assertTrue(elements(xml) > 2 * elements(text) && text.length() < xml.length(), xml);
        assertNull(SchemaValidator.shared().problemWith(text), text);
        ControlMlElement fromText = Xml.element(text);
        ControlMlElement fromXml = Xml.element(xml);
        assertNull(fromText.defect(), () -> String.valueOf(fromText.defect()));
        assertEquals(fromXml.payload(), fromText.payload());
        assertEquals(Samples.VALUES.get(resource), resource.codec().decode(fromText.payload()));
    }

    @ParameterizedTest
    @MethodSource("unstructured")
    void otherResourcesAlwaysTravelAsXml(Resource<?, ?> resource) {
        Object value = Samples.VALUES.get(resource);
        ControlMlElement element = resource.isSettable() ? ControlMlElement.request(ControlMlType.SET, ID, resource
                .name(), encode(resource, value)) : ControlMlElement.result(ID, resource.name(), encode(resource,
                        value));

        assertEquals(Xml.xml(element.withTextForm(false)), Xml.xml(element));
        assertFalse(Xml.xml(element).contains("DataStream"));
    }

    @Test
    void aValueThatDoesNotFitFallsBackToXml() {
        // the structure names cm.position's fields, but a writer may hold a record of another shape
        SweComponent other = new DataRecord(List.of(new DataRecord.Field("x", new Quantity("m", 1))));
        ControlMlElement element = ControlMlElement.result(ID, "cm.position", other);

        assertEquals(Xml.xml(element.withTextForm(false)), Xml.xml(element));
    }

    private static final DataRecord SHAPE = new DataRecord(List.of(new DataRecord.Field("t", new Time(Instant.EPOCH)),
            new DataRecord.Field("note", new Text("x")), new DataRecord.Field("ok", new SweBoolean(true)),
            new DataRecord.Field("m", new DataArray("row", List.of(DataArray.Column.quantity("a", "m"), DataArray.Column
                    .count("n")), List.of(new double[] { 0, 0 }, new double[] { 0, 0 })))));

    @Test
    void templateWritesLeavesInDocumentOrderAndRebuildsTheRecord() throws Exception {
        RecordTemplate template = new RecordTemplate(SHAPE);
        DataRecord value = new DataRecord(List.of(new DataRecord.Field("t", new Time(Instant.parse(
                "2026-11-21T10:15:30.5Z"))), new DataRecord.Field("note", new Text("a<b")), new DataRecord.Field("ok",
                        new SweBoolean(false)), new DataRecord.Field("m", new DataArray("row", List.of(DataArray.Column
                                .quantity("a", "m"), DataArray.Column.count("n")), List.of(new double[] { 1.5, 2 },
                                        new double[] { -0.25, 7 })))));
        StringBuilder out = new StringBuilder();

        template.writeValues(value, out);

        assertEquals(7, template.tokenCount());
        assertEquals("2026-11-21T10:15:30.500Z,a&lt;b,false,1.5,2,-0.25,7", out.toString());
        assertEquals(value, template.read("2026-11-21T10:15:30.500Z,a<b,false,1.5,2,-0.25,7"));
    }

    @Test
    void textThatHoldsASeparatorDoesNotFit() {
        RecordTemplate template = new RecordTemplate(SHAPE);
        for (String note : new String[] { "two words", "a,b", "", "tab\there" }) {
            DataRecord value = new DataRecord(List.of(SHAPE.fields().get(0), new DataRecord.Field("note", new Text(
                    note)), SHAPE.fields().get(2), SHAPE.fields().get(3)));
            assertFalse(template.fits(value), note);
            assertThrows(IllegalArgumentException.class, () -> template.writeValues(value, new StringBuilder()));
        }
    }

    @Test
    void otherShapesDoNotFit() {
        RecordTemplate template = new RecordTemplate(SHAPE);
        DataArray oneRow = new DataArray("row", List.of(DataArray.Column.quantity("a", "m"), DataArray.Column.count(
                "n")), List.<double[]>of(new double[] { 0, 0 }));
        DataArray otherUnit = new DataArray("row", List.of(DataArray.Column.quantity("a", "cm"), DataArray.Column.count(
                "n")), List.of(new double[] { 0, 0 }, new double[] { 0, 0 }));

        assertTrue(template.fits(SHAPE));
        assertFalse(template.fits(new DataRecord(List.of(SHAPE.fields().get(0), SHAPE.fields().get(1), SHAPE.fields()
                .get(2), new DataRecord.Field("m", oneRow)))), "row count");
        assertFalse(template.fits(new DataRecord(List.of(SHAPE.fields().get(0), SHAPE.fields().get(1), SHAPE.fields()
                .get(2), new DataRecord.Field("m", otherUnit)))), "unit");
        assertFalse(template.fits(new DataRecord(List.of(SHAPE.fields().get(1), SHAPE.fields().get(0), SHAPE.fields()
                .get(2), SHAPE.fields().get(3)))), "field order");
        assertFalse(template.fits(new Quantity("m", 1)), "not a record");
    }

    @Test
    void badTokensAreMalformed() {
        RecordTemplate template = new RecordTemplate(SHAPE);
        for (String values : new String[] { "2026-11-21T10:15:30Z,a,true,1,2,3", "2026-11-21T10:15:30Z,a,true,1,2,3,4,5",
            "2026-11-21 10:15:30,a,true,1,2,3,4", "2026-11-21T10:15:30Z,a,yes,1,2,3,4",
            "2026-11-21T10:15:30Z,a,true,1,2.5,3,4", "2026-11-21T10:15:30Z,,true,1,2,3,4",
            "2026-11-21T10:15:30Z,a,true,1,2,3,4 2026-11-21T10:15:30Z,a,true,1,2,3,4" }) {
            SweFormatException e = assertThrows(SweFormatException.class, () -> template.read(values), values);
            assertEquals(SweFormatException.Problem.MALFORMED, e.problem(), values);
        }
    }

    private static long elements(String xml) {
        return xml.chars().filter(c -> c == '<').count() - xml.split("</", -1).length + 1;
    }

    @SuppressWarnings("unchecked")
    private static <T> SweComponent encode(Resource<T, ?> resource, Object value) {
        return ((PayloadCodec<T>) resource.codec()).encode((T) value);
    }
}
