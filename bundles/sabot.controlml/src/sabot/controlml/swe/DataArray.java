package sabot.controlml.swe;

import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Objects;

/**
 * A table of numbers (SWE {@code DataArray} whose element type is a {@code DataRecord} of value-less
 * {@code Quantity}/{@code Count} columns), values in the text encoding {@code tokenSeparator=","
 * blockSeparator=" "}. ControlML uses it for trajectories, obstacle lists, gains and map cells.
 *
 * @param rowName     the elementType's name (e.g. {@code point})
 * @param columns     the columns; never empty
 * @param rows        the values, one array of {@code columns.size()} numbers per row, each in its column's unit;
 *                    Count columns hold integral values
 */
public record DataArray(String rowName, List<Column> columns, List<double[]> rows) implements SweComponent {

    /**
     * A column of the array.
     *
     * @param name the field name in the element type
     * @param uom  UCUM code for a Quantity column, or null for a Count column
     */
    public record Column(String name, String uom) {
        public Column {
            Objects.requireNonNull(name, "name");
        }

        /** @return a Quantity column */
        public static Column quantity(String name, String uom) {
            return new Column(name, Objects.requireNonNull(uom, "uom"));
        }

        /** @return a Count column */
        public static Column count(String name) {
            return new Column(name, null);
        }

        /** @return true for a Count column */
        public boolean isCount() {
            return uom == null;
        }
    }

    public DataArray {
        Objects.requireNonNull(rowName, "rowName");
        columns = List.copyOf(columns);
        if (columns.isEmpty()) {
            throw new IllegalArgumentException("a DataArray needs at least one column");
        }
        List<double[]> copy = new ArrayList<>(rows.size());
        for (double[] row : rows) {
            if (row.length != columns.size()) {
                throw new IllegalArgumentException("row of " + row.length + " values for " + columns.size()
                        + " columns");
            }
            copy.add(row.clone());
        }
        rows = List.copyOf(copy);
    }

    @Override
    public List<double[]> rows() {
        List<double[]> copy = new ArrayList<>(rows.size());
        for (double[] row : rows) {
            copy.add(row.clone());
        }
        return copy;
    }

    /** @return the number of rows */
    public int size() {
        return rows.size();
    }

    /** @return one value, without copying */
    public double value(int row, int column) {
        return rows.get(row)[column];
    }

    @Override
    public String elementName() {
        return "DataArray";
    }

    @Override
    public boolean equals(Object o) {
        if (!(o instanceof DataArray other) || !rowName.equals(other.rowName) || !columns.equals(
                other.columns) || rows.size() != other.rows.size()) {
            return false;
        }
        for (int i = 0; i < rows.size(); i++) {
            if (!Arrays.equals(rows.get(i), other.rows.get(i))) {
                return false;
            }
        }
        return true;
    }

    @Override
    public int hashCode() {
        int h = Objects.hash(rowName, columns);
        for (double[] row : rows) {
            h = 31 * h + Arrays.hashCode(row);
        }
        return h;
    }

    @Override
    public String toString() {
        return "DataArray[" + rowName + ", " + columns + ", " + rows.size() + " rows]";
    }
}
