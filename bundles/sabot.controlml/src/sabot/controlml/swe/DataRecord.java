package sabot.controlml.swe;

import java.util.HashSet;
import java.util.List;
import java.util.Objects;
import java.util.Set;

/**
 * An ordered list of named fields (SWE {@code DataRecord}). Field names are unique.
 *
 * @param fields the fields in document order; never null, never empty (SWE requires at least one field)
 */
public record DataRecord(List<Field> fields) implements SweComponent {

    /** Up to this many fields, names are checked for duplicates pair by pair; a set beyond (a payload may be large). */
    private static final int PAIRWISE_CHECK = 16;

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
        if (fields.size() <= PAIRWISE_CHECK) {
            // the usual handful of fields: comparing pairs costs less than a set built for each record read
            for (int i = 1; i < fields.size(); i++) {
                String name = fields.get(i).name();
                for (int j = 0; j < i; j++) {
                    if (fields.get(j).name().equals(name)) {
                        throw new IllegalArgumentException("duplicate field name " + name);
                    }
                }
            }
        } else {
            Set<String> seen = new HashSet<>();
            for (Field f : fields) {
                if (!seen.add(f.name())) {
                    throw new IllegalArgumentException("duplicate field name " + f.name());
                }
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
