package sabot.controlml.swe;

import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Objects;

/**
 * An ordered list of named fields (SWE {@code DataRecord}). Field names are unique.
 *
 * @param fields the fields in document order; never null, never empty (SWE requires at least one field)
 */
public record DataRecord(List<Field> fields) implements SweComponent {

    /**
     * @param name      the field name (an NCName)
     * @param component the field's value
     */
    public record Field(String name, SweComponent component) {
        public Field {
            Objects.requireNonNull(name, "name");
            Objects.requireNonNull(component, "component");
        }
    }

    public DataRecord {
        fields = List.copyOf(fields);
        if (fields.isEmpty()) {
            throw new IllegalArgumentException("a DataRecord needs at least one field");
        }
        Map<String, Field> seen = new LinkedHashMap<>();
        for (Field f : fields) {
            if (seen.put(f.name(), f) != null) {
                throw new IllegalArgumentException("duplicate field name " + f.name());
            }
        }
    }

    /** @return the field with this name, or null when there is none */
    public SweComponent get(String name) {
        for (Field f : fields) {
            if (f.name().equals(name)) {
                return f.component();
            }
        }
        return null;
    }

    @Override
    public String elementName() {
        return "DataRecord";
    }
}
