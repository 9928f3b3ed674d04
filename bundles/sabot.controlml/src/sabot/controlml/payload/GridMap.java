package sabot.controlml.payload;

import java.util.Arrays;
import java.util.Objects;

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
}
