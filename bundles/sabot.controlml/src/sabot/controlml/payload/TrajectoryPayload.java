package sabot.controlml.payload;

import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.swe.DataArray;
import sabot.controlml.swe.SweComponent;

/**
 * {@code cm.trajectory}: the planned (get) or imposed (set) timed path, as it travels: a table of samples. What a
 * controller follows is a {@code sabot.model.path.Trajectory}, of which this is a sampling.
 *
 * @param start  the time of {@code t = 0}; never null
 * @param points samples with non-decreasing {@code t}; never null
 */
public record TrajectoryPayload(Instant start, List<TrajectoryPoint> points) {
    public TrajectoryPayload {
        Objects.requireNonNull(start, "start");
        points = List.copyOf(points);
    }

    private static final List<DataArray.Column> TRAJECTORY_COLUMNS = List.of(DataArray.Column.quantity("t", "s"),
            DataArray.Column.quantity("x", "m"), DataArray.Column.quantity("y", "m"), DataArray.Column.quantity(
                    "theta", "rad"), DataArray.Column.quantity("v", "m/s"), DataArray.Column.quantity("omega",
                            "rad/s"));

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<TrajectoryPayload> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(TrajectoryPayload t) {
            List<double[]> rows = new ArrayList<>(t.points().size());
            for (TrajectoryPoint p : t.points()) {
                rows.add(new double[] { p.t(), p.x(), p.y(), p.theta(), p.v(), p.omega() });
            }
            return new RecordBuilder().time("start", t.start()).add("points", new DataArray("point",
                    TRAJECTORY_COLUMNS, rows)).build();
        }

        @Override
        public TrajectoryPayload decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "start", "points");
            List<double[]> rows = r.array("points", TRAJECTORY_COLUMNS, 4096);
            List<TrajectoryPoint> points = new ArrayList<>(rows.size());
            double previous = 0;
            for (double[] row : rows) {
                if (row[0] < previous) {
                    throw new PayloadException(ControlMlCondition.INVALID_VALUE,
                            "trajectory times must start at >= 0 s and not decrease");
                }
                previous = row[0];
                points.add(new TrajectoryPoint(row[0], row[1], row[2], row[3], row[4], row[5]));
            }
            return new TrajectoryPayload(r.time("start"), points);
        }
    };
}
