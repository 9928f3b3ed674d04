package sabot.controlml.payload;

import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.swe.DataArray;
import sabot.controlml.swe.SweComponent;

/**
 * {@code cm.obstacles}: what the sensors see.
 *
 * @param time      when; never null
 * @param obstacles the discs; never null
 */
public record Obstacles(Instant time, List<Obstacle> obstacles) {
    public Obstacles {
        Objects.requireNonNull(time, "time");
        obstacles = List.copyOf(obstacles);
    }

    private static final List<DataArray.Column> OBSTACLE_COLUMNS = List.of(DataArray.Column.quantity("x", "m"),
            DataArray.Column.quantity("y", "m"), DataArray.Column.quantity("radius", "m"));

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<Obstacles> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(Obstacles o) {
            List<double[]> rows = new ArrayList<>();
            for (Obstacle ob : o.obstacles()) {
                rows.add(new double[] { ob.x(), ob.y(), ob.radius() });
            }
            return new RecordBuilder().time("time", o.time()).add("obstacles", new DataArray("obstacle",
                    OBSTACLE_COLUMNS, rows)).build();
        }

        @Override
        public Obstacles decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "time", "obstacles");
            List<Obstacle> list = new ArrayList<>();
            for (double[] row : r.array("obstacles", OBSTACLE_COLUMNS, 1024)) {
                if (row[2] < 0) {
                    throw new PayloadException(ControlMlCondition.INVALID_VALUE, "negative obstacle radius");
                }
                list.add(new Obstacle(row[0], row[1], row[2]));
            }
            return new Obstacles(r.time("time"), list);
        }
    };
}
