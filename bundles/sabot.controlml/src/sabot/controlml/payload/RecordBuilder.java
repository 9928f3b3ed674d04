package sabot.controlml.payload;

import java.time.Instant;
import java.util.ArrayList;
import java.util.List;

import sabot.controlml.swe.Category;
import sabot.controlml.swe.Count;
import sabot.controlml.swe.DataRecord;
import sabot.controlml.swe.Quantity;
import sabot.controlml.swe.SweBoolean;
import sabot.controlml.swe.SweComponent;
import sabot.controlml.swe.Text;
import sabot.controlml.swe.Time;

/** Builds a payload {@link DataRecord} field by field, in the order of the resource's schema. */
public final class RecordBuilder {

    private final List<DataRecord.Field> fields = new ArrayList<>();

    /** @return a quantity field (value in {@code uom}) */
    public RecordBuilder quantity(String name, String uom, double value) {
        return add(name, new Quantity(uom, value));
    }

    /** @return a count field */
    public RecordBuilder count(String name, long value) {
        return add(name, new Count(value));
    }

    /** @return a time field */
    public RecordBuilder time(String name, Instant value) {
        return add(name, new Time(value));
    }

    /** @return a text field */
    public RecordBuilder text(String name, String value) {
        return add(name, new Text(value));
    }

    /** @return a category field */
    public RecordBuilder category(String name, String value) {
        return add(name, new Category(value));
    }

    /** @return a boolean field */
    public RecordBuilder bool(String name, boolean value) {
        return add(name, new SweBoolean(value));
    }

    /** @return any component as a field */
    public RecordBuilder add(String name, SweComponent component) {
        fields.add(new DataRecord.Field(name, component));
        return this;
    }

    /** @return the record */
    public DataRecord build() {
        return new DataRecord(fields);
    }
}
