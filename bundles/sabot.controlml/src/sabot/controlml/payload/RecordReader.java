package sabot.controlml.payload;

import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.OptionalDouble;
import java.util.Set;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.swe.Category;
import sabot.controlml.swe.Count;
import sabot.controlml.swe.DataArray;
import sabot.controlml.swe.DataRecord;
import sabot.controlml.swe.Quantity;
import sabot.controlml.swe.SweBoolean;
import sabot.controlml.swe.SweComponent;
import sabot.controlml.swe.SweXml;
import sabot.controlml.swe.Text;
import sabot.controlml.swe.Time;
import sabot.controlml.swe.Ucum;

/**
 * Reads a payload {@link DataRecord} against a schema, field by field: the record must have exactly the expected
 * fields (any order), each of the expected component type; quantities are converted to their canonical unit and must
 * be finite and within range. Problems are reported with the field's path, e.g. {@code pose.theta}.
 */
public final class RecordReader {

    /** A lower bound of {@link #quantity(String, String, double, double)} that means "greater than 0". */
    public static final double POSITIVE = Double.MIN_VALUE;
    /** An upper bound of {@link #quantity(String, String, double, double)} that means "any finite value". */
    public static final double UNBOUNDED = Double.POSITIVE_INFINITY;

    private final DataRecord record;
    private final String path;

    private RecordReader(DataRecord record, String path) {
        this.record = record;
        this.path = path;
    }

    /**
     * @param payload the payload
     * @param fields  the exact field names the record must have
     * @return a reader for a payload that is a DataRecord with exactly these fields
     */
    public static RecordReader of(SweComponent payload, String... fields) throws PayloadException {
        if (!(payload instanceof DataRecord r)) {
            throw malformed("payload must be a DataRecord, not a " + (payload == null ? "missing payload" : payload
                    .elementName()));
        }
        RecordReader reader = new RecordReader(r, "");
        reader.expectFields(fields);
        return reader;
    }

    private void expectFields(String... names) throws PayloadException {
        // a record's field names are unique: all expected and as many as expected means all present
        for (DataRecord.Field f : record.fields()) {
            if (!contains(names, f.name())) {
                throw malformed("unexpected field " + path + f.name() + " (expected " + String.join(", ", names)
                        + ")");
            }
        }
        if (record.fields().size() != names.length) {
            for (String n : names) {
                if (record.get(n) == null) {
                    throw malformed("missing field " + path + n);
                }
            }
        }
    }

    private static boolean contains(String[] names, String name) {
        for (String n : names) {
            if (n.equals(name)) {
                return true;
            }
        }
        return false;
    }

    private SweComponent field(String name) {
        return record.get(name);
    }

    /** @return a field's quantity in the canonical unit, which must be finite */
    public double quantity(String name, String canonicalUom) throws PayloadException {
        return quantity(name, canonicalUom, Double.NEGATIVE_INFINITY, Double.POSITIVE_INFINITY);
    }

    /** @return a field's quantity in the canonical unit, finite and within [min, max] */
    public double quantity(String name, String canonicalUom, double min, double max) throws PayloadException {
        if (!(field(name) instanceof Quantity q)) {
            throw malformed(path + name + " must be a Quantity");
        }
        return toCanonical(path, name, -1, null, q.value(), q.uom(), canonicalUom, min, max);
    }

    /**
     * @param path the path of the field's record, the field's name, and for a cell of an array its row and column
     *             (row -1 otherwise): the name in messages, built only for one
     */
    private static double toCanonical(String path, String field, int row, String column, double value, String uom,
            String canonicalUom, double min, double max) throws PayloadException {
        OptionalDouble v = Ucum.toCanonical(value, uom, canonicalUom);
        if (v.isEmpty()) {
            throw new PayloadException(ControlMlCondition.WRONG_UNIT, where(path, field, row, column) + " is in '" + uom
                    + "', expected '" + canonicalUom + "' (or a unit of the same dimension)");
        }
        double d = v.getAsDouble();
        if (!Double.isFinite(d)) {
            throw new PayloadException(ControlMlCondition.INVALID_VALUE, where(path, field, row, column)
                    + " must be finite, was " + SweXml.formatDouble(value));
        }
        if (d < min || d > max) {
            throw new PayloadException(ControlMlCondition.INVALID_VALUE, where(path, field, row, column) + " = " + d
                    + " " + canonicalUom + " is outside [" + min + ", " + max + "]");
        }
        return d;
    }

    private static String where(String path, String field, int row, String column) {
        return path + field + (row < 0 ? "" : "[" + row + "]." + column);
    }

    /** @return a field's count within [min, max] */
    public long count(String name, long min, long max) throws PayloadException {
        if (!(field(name) instanceof Count c)) {
            throw malformed(path + name + " must be a Count");
        }
        if (c.value() < min || c.value() > max) {
            throw new PayloadException(ControlMlCondition.INVALID_VALUE, path + name + " = " + c.value()
                    + " is outside [" + min + ", " + max + "]");
        }
        return c.value();
    }

    /** @return a field's time stamp */
    public Instant time(String name) throws PayloadException {
        if (!(field(name) instanceof Time t)) {
            throw malformed(path + name + " must be a Time");
        }
        return t.value();
    }

    /** @return a field's text, at most {@code maxLength} characters and free of control characters */
    public String text(String name, int maxLength) throws PayloadException {
        if (!(field(name) instanceof Text t)) {
            throw malformed(path + name + " must be a Text");
        }
        if (t.value().length() > maxLength || t.value().chars().anyMatch(ch -> ch < 0x20 && ch != '\t')) {
            throw new PayloadException(ControlMlCondition.INVALID_VALUE, path + name
                    + " is too long or holds control characters");
        }
        return t.value();
    }

    /** @return a field's category code, one of {@code allowed} */
    public String category(String name, Set<String> allowed) throws PayloadException {
        if (!(field(name) instanceof Category c)) {
            throw malformed(path + name + " must be a Category");
        }
        if (!allowed.contains(c.value())) {
            throw new PayloadException(ControlMlCondition.INVALID_VALUE, path + name + " = '" + c.value()
                    + "' is not one of " + allowed);
        }
        return c.value();
    }

    /** @return a field's flag */
    public boolean bool(String name) throws PayloadException {
        if (!(field(name) instanceof SweBoolean b)) {
            throw malformed(path + name + " must be a Boolean");
        }
        return b.value();
    }

    /** @return a reader for a nested record with exactly these fields */
    public RecordReader record(String name, String... fields) throws PayloadException {
        if (!(field(name) instanceof DataRecord r)) {
            throw malformed(path + name + " must be a DataRecord");
        }
        RecordReader reader = new RecordReader(r, path + name + ".");
        reader.expectFields(fields);
        return reader;
    }

    /**
     * @param name     the field
     * @param columns  the expected columns (names in order; Quantity columns with their canonical unit)
     * @param maxRows  most rows accepted
     * @return the rows, each value in its column's canonical unit and finite
     */
    public List<double[]> array(String name, List<DataArray.Column> columns, int maxRows) throws PayloadException {
        if (!(field(name) instanceof DataArray a)) {
            throw malformed(path + name + " must be a DataArray");
        }
        if (a.columns().size() != columns.size()) {
            throw malformed(path + name + " must have the columns " + names(columns));
        }
        for (int c = 0; c < columns.size(); c++) {
            DataArray.Column want = columns.get(c);
            DataArray.Column got = a.columns().get(c);
            if (!want.name().equals(got.name()) || want.isCount() != got.isCount()) {
                throw malformed(path + name + " must have the columns " + names(columns));
            }
        }
        if (a.size() > maxRows) {
            throw new PayloadException(ControlMlCondition.INVALID_VALUE, path + name + " has " + a.size()
                    + " rows, at most " + maxRows + " allowed");
        }
        List<double[]> rows = new ArrayList<>(a.size());
        for (int r = 0; r < a.size(); r++) {
            double[] row = new double[columns.size()];
            for (int c = 0; c < columns.size(); c++) {
                DataArray.Column want = columns.get(c);
                double v = a.value(r, c);
                row[c] = want.isCount() ? v : toCanonical(path, name, r, want.name(), v, a.columns().get(c).uom(),
                        want.uom(), Double.NEGATIVE_INFINITY, Double.POSITIVE_INFINITY);
            }
            rows.add(row);
        }
        return rows;
    }

    private static String names(List<DataArray.Column> columns) {
        List<String> n = new ArrayList<>();
        for (DataArray.Column c : columns) {
            n.add(c.name() + (c.isCount() ? ":Count" : ":" + c.uom()));
        }
        return n.toString();
    }

    static PayloadException malformed(String message) {
        return new PayloadException(ControlMlCondition.MALFORMED_PAYLOAD, message);
    }

    /**
     * @return field names {@code count, <prefix>0 .. <prefix>n-1} of a record whose {@code count} field says n (a
     *         list of records as a record, for {@link #of})
     * @throws PayloadException when n is negative or over {@code max}
     */
    public static String[] indexedFields(SweComponent payload, String prefix, int max) throws PayloadException {
        long n = 0;
        if (payload instanceof DataRecord r && r.get("count") instanceof Count c) {
            n = c.value();
        }
        if (n < 0 || n > max) {
            throw new PayloadException(ControlMlCondition.INVALID_VALUE, "count must be 0.." + max);
        }
        String[] names = new String[(int) n + 1];
        names[0] = "count";
        for (int i = 0; i < n; i++) {
            names[i + 1] = prefix + i;
        }
        return names;
    }
}
