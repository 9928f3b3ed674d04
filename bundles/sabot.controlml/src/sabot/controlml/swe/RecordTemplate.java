package sabot.controlml.swe;

import java.time.Instant;
import java.time.format.DateTimeParseException;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;

/**
 * The structure of a {@link DataRecord} agreed in advance, so that a value travels as one block of the SWE text
 * encoding instead of an element per field: SWE Common 2.0's {@code DataStream} whose {@code elementType} is given by
 * reference ({@code xlink:href}) and whose {@code values} hold the record's tokens (OGC 08-094r1, clause 10.2, text
 * encoding rules: the scalar leaves in document order, one token each; the rows of a fixed-size array in order).
 * This is the pattern of SOS 2.0's result template (GetResultTemplate / GetResult): structure once, values compact.
 * <p>
 * The structure is taken from a prototype record: field names and order, component types, Quantity units, array
 * columns and row counts. A value {@link #fits} when it has that structure and every Text or Category value is a
 * non-empty token without separators; {@link #read} rebuilds exactly the record the XML form would have given, so
 * payload codecs see no difference between the two forms.
 */
public final class RecordTemplate {

    private final DataRecord prototype;
    private final int tokens;

    /**
     * @param prototype a record of the structure (its values do not matter); scalar fields, nested records and
     *                  DataArrays, whose row count becomes fixed
     */
    public RecordTemplate(DataRecord prototype) {
        this.prototype = Objects.requireNonNull(prototype, "prototype");
        this.tokens = count(prototype);
    }

    private static int count(SweComponent c) {
        return switch (c) {
            case DataRecord r -> r.fields().stream().mapToInt(f -> count(f.component())).sum();
            case DataArray a -> a.size() * a.columns().size();
            default -> 1;
        };
    }

    /** @return the number of tokens of a value */
    public int tokenCount() {
        return tokens;
    }

    /** @return true when {@code value} has this structure and all its tokens can be written */
    public boolean fits(SweComponent value) {
        return fits(prototype, value);
    }

    private static boolean fits(SweComponent shape, SweComponent value) {
        return switch (shape) {
            case DataRecord r -> {
                if (!(value instanceof DataRecord v) || v.fields().size() != r.fields().size()) {
                    yield false;
                }
                for (int i = 0; i < r.fields().size(); i++) {
                    DataRecord.Field a = r.fields().get(i);
                    DataRecord.Field b = v.fields().get(i);
                    if (!a.name().equals(b.name()) || !fits(a.component(), b.component())) {
                        yield false;
                    }
                }
                yield true;
            }
            case DataArray a -> value instanceof DataArray v && v.rowName().equals(a.rowName()) && v.columns().equals(a
                    .columns()) && v.size() == a.size();
            case Quantity q -> value instanceof Quantity v && v.uom().equals(q.uom());
            case Text t -> value instanceof Text v && isToken(v.value());
            case Category t -> value instanceof Category v && isToken(v.value());
            default -> value.getClass() == shape.getClass();
        };
    }

    private static boolean isToken(String s) {
        if (s.isEmpty()) {
            return false;
        }
        for (int i = 0; i < s.length(); i++) {
            char ch = s.charAt(i);
            if (ch == ',' || Character.isWhitespace(ch) || Character.isISOControl(ch)) {
                return false;
            }
        }
        return true;
    }

    /**
     * Writes the tokens of a value that {@link #fits}, separated by {@value Swe#TOKEN_SEPARATOR}, XML-escaped.
     *
     * @throws IllegalArgumentException when the value does not fit
     */
    public void writeValues(SweComponent value, StringBuilder out) {
        if (!fits(value)) {
            throw new IllegalArgumentException("value does not have the template's structure");
        }
        writeTokens(value, out);
        out.setLength(out.length() - Swe.TOKEN_SEPARATOR.length()); // the last separator
    }

    private static void writeTokens(SweComponent c, StringBuilder out) {
        switch (c) {
            case DataRecord r -> {
                for (DataRecord.Field f : r.fields()) {
                    writeTokens(f.component(), out);
                }
                return;
            }
            case DataArray a -> {
                for (int row = 0; row < a.size(); row++) {
                    for (int col = 0; col < a.columns().size(); col++) {
                        double v = a.value(row, col);
                        out.append(a.columns().get(col).isCount() ? Long.toString((long) v) : SweXml.formatDouble(v))
                                .append(Swe.TOKEN_SEPARATOR);
                    }
                }
                return;
            }
            case Quantity q -> out.append(SweXml.formatDouble(q.value()));
            case Count n -> out.append(n.value());
            case Time t -> IsoInstant.format(t.value(), out);
            case SweBoolean b -> out.append(b.value());
            case Text t -> SweXml.escape(t.value(), out);
            case Category t -> SweXml.escape(t.value(), out);
        }
        out.append(Swe.TOKEN_SEPARATOR);
    }

    /**
     * Rebuilds a record from the text of a {@code values} element: exactly {@link #tokenCount()} tokens in one block.
     *
     * @throws SweFormatException ({@link SweFormatException.Problem#MALFORMED}) when the text is not one block of the
     *                            right number of tokens, each in its component's lexical space
     */
    public DataRecord read(String values) throws SweFormatException {
        String block = values.strip();
        for (int i = 0; i < block.length(); i++) {
            if (Character.isWhitespace(block.charAt(i))) {
                throw malformed("a record's values are one block (no '" + Swe.BLOCK_SEPARATOR + "')");
            }
        }
        String[] parts = new String[tokens];
        int found = 0;
        int start = 0;
        while (!block.isEmpty()) {
            int end = block.indexOf(',', start);
            if (found < tokens) {
                parts[found] = end < 0 ? block.substring(start) : block.substring(start, end);
            }
            found++;
            if (end < 0) {
                break;
            }
            start = end + 1;
        }
        if (found != tokens) {
            throw malformed(found + " values for a record of " + tokens);
        }
        int[] next = { 0 };
        return (DataRecord) rebuild(prototype, parts, next);
    }

    private static SweComponent rebuild(SweComponent shape, String[] parts, int[] next) throws SweFormatException {
        switch (shape) {
            case DataRecord r -> {
                List<DataRecord.Field> fields = new ArrayList<>(r.fields().size());
                for (DataRecord.Field f : r.fields()) {
                    fields.add(new DataRecord.Field(f.name(), rebuild(f.component(), parts, next)));
                }
                return new DataRecord(fields);
            }
            case DataArray a -> {
                List<double[]> rows = new ArrayList<>(a.size());
                for (int row = 0; row < a.size(); row++) {
                    double[] values = new double[a.columns().size()];
                    for (int col = 0; col < values.length; col++) {
                        String token = parts[next[0]++];
                        values[col] = a.columns().get(col).isCount() ? SweXml.parseLong(token) : SweXml.parseDouble(
                                token);
                    }
                    rows.add(values);
                }
                return new DataArray(a.rowName(), a.columns(), rows);
            }
            default -> {
                // a scalar
            }
        }
        String token = parts[next[0]++];
        return switch (shape) {
            case Quantity q -> new Quantity(q.uom(), SweXml.parseDouble(token));
            case Count n -> new Count(SweXml.parseLong(token));
            case Time t -> {
                try {
                    yield new Time(IsoInstant.parse(token));
                } catch (DateTimeParseException e) {
                    throw malformed("not an ISO 8601 UTC time stamp: '" + SweXml.abbreviate(token) + "'");
                }
            }
            case SweBoolean b -> switch (token) {
                case "true", "1" -> new SweBoolean(true);
                case "false", "0" -> new SweBoolean(false);
                default -> throw malformed("not an xs:boolean: '" + SweXml.abbreviate(token) + "'");
            };
            case Text t -> new Text(nonEmpty(token));
            case Category t -> new Category(nonEmpty(token));
            default -> throw new IllegalStateException(shape.toString());
        };
    }

    private static String nonEmpty(String token) throws SweFormatException {
        if (token.isEmpty()) {
            throw malformed("empty token");
        }
        return token;
    }

    private static SweFormatException malformed(String message) {
        return new SweFormatException(SweFormatException.Problem.MALFORMED, message);
    }
}
