package sabot.motion.sim;

import java.util.Arrays;

/** Time series of one run, one row per control step, in growable primitive columns. */
public final class Trace {

    /** Column names, in CSV order. */
    public static final String[] COLUMNS = { "run", "t_s", "ref_x_m", "ref_y_m", "ref_theta_rad", "true_x_m",
            "true_y_m", "true_theta_rad", "est_x_m", "est_y_m", "est_theta_rad", "v_cmd_mps", "w_cmd_radps",
            "error_m", "estimate_error_m" };

    private double[][] cols = new double[COLUMNS.length][1024];
    private String[] status = new String[1024];
    private int size;

    void add(String statusName, double... row) {
        if (row.length != COLUMNS.length) {
            throw new IllegalArgumentException("row has " + row.length + " values");
        }
        if (size == status.length) {
            int cap = size * 2;
            for (int i = 0; i < cols.length; i++) {
                cols[i] = Arrays.copyOf(cols[i], cap);
            }
            status = Arrays.copyOf(status, cap);
        }
        for (int i = 0; i < row.length; i++) {
            cols[i][size] = row[i];
        }
        status[size] = statusName;
        size++;
    }

    void append(Trace other) {
        for (int r = 0; r < other.size; r++) {
            double[] row = new double[COLUMNS.length];
            for (int c = 0; c < row.length; c++) {
                row[c] = other.cols[c][r];
            }
            add(other.status[r], row);
        }
    }

    public int size() {
        return size;
    }

    /** @return the value of column {@code c} in row {@code r} */
    public double get(int r, int c) {
        return cols[c][r];
    }

    /** @return the controller status of row {@code r} */
    public String status(int r) {
        return status[r];
    }

    /** @return the index of a column by name */
    public static int column(String name) {
        for (int i = 0; i < COLUMNS.length; i++) {
            if (COLUMNS[i].equals(name)) {
                return i;
            }
        }
        throw new IllegalArgumentException(name);
    }
}
