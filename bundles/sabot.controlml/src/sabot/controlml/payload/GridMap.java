package sabot.controlml.payload;

import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Objects;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.swe.DataArray;
import sabot.controlml.swe.SweComponent;
import sabot.model.geometry.Pose2D;

/**
 * {@code cm.map}: an occupancy grid small enough for one payload (larger maps travel as files, {@code cm.fs.*}).
 *
 * @param resolution cell edge in metres, &gt; 0
 * @param width      cells per row
 * @param height     rows
 * @param origin     pose of cell (0,0)'s lower-left corner in the map frame
 * @param cells      row-major from the bottom row, occupancy 0..100 or -1 for unknown (ROS map_server values)
 */
public record GridMap(double resolution, int width, int height, Pose2D origin, byte[] cells) {
    public GridMap {
        Objects.requireNonNull(origin, "origin");
        cells = cells.clone();
        if (cells.length != (long) width * height) {
            throw new IllegalArgumentException(cells.length + " cells for " + width + "x" + height);
        }
    }

    @Override
    public byte[] cells() {
        return cells.clone();
    }

    @Override
    public boolean equals(Object o) {
        return o instanceof GridMap m && m.resolution == resolution && m.width == width && m.height == height && m.origin
                .equals(origin) && Arrays.equals(m.cells, cells);
    }

    @Override
    public int hashCode() {
        return Objects.hash(resolution, width, height, origin) * 31 + Arrays.hashCode(cells);
    }

    @Override
    public String toString() {
        return "GridMap[" + width + "x" + height + " @ " + resolution + " m, origin " + origin + "]";
    }

    private static final List<DataArray.Column> CELL_COLUMNS = List.of(DataArray.Column.count("occupancy"));

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<GridMap> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(GridMap m) {
            byte[] cells = m.cells();
            List<double[]> rows = new ArrayList<>(cells.length);
            for (byte c : cells) {
                rows.add(new double[] { c });
            }
            return new RecordBuilder().quantity("resolution", "m", m.resolution()).count("width", m.width()).count(
                    "height", m.height()).add("origin", new RecordBuilder().quantity("x", "m", m.origin().x())
                            .quantity("y", "m", m.origin().y()).quantity("theta", "rad", m.origin().theta()).build())
                    .add("cells", new DataArray("cell", CELL_COLUMNS, rows)).build();
        }

        @Override
        public GridMap decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "resolution", "width", "height", "origin", "cells");
            RecordReader o = r.record("origin", "x", "y", "theta");
            int width = (int) r.count("width", 1, 4096);
            int height = (int) r.count("height", 1, 4096);
            List<double[]> rows = r.array("cells", CELL_COLUMNS, 1 << 16);
            if (rows.size() != width * height) {
                throw new PayloadException(ControlMlCondition.INVALID_VALUE, "map of " + width + "x" + height
                        + " needs " + width * height + " cells, has " + rows.size());
            }
            byte[] cells = new byte[rows.size()];
            for (int i = 0; i < cells.length; i++) {
                double v = rows.get(i)[0];
                if (v < -1 || v > 100) {
                    throw new PayloadException(ControlMlCondition.INVALID_VALUE, "cell " + i + " = " + v
                            + " is not an occupancy (-1 unknown, 0..100)");
                }
                cells[i] = (byte) v;
            }
            return new GridMap(r.quantity("resolution", "m", RecordReader.POSITIVE, RecordReader.UNBOUNDED), width,
                    height, new Pose2D(o.quantity("x", "m"), o.quantity("y", "m"), o.quantity("theta", "rad")), cells);
        }
    };
}
