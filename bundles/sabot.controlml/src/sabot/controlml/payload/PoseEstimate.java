package sabot.controlml.payload;

import java.time.Instant;
import java.util.List;
import java.util.Objects;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.swe.DataArray;
import sabot.controlml.swe.SweComponent;
import sabot.model.geometry.Pose2D;

/**
 * {@code cm.position}: the localizer's pose estimate in the map frame.
 *
 * @param time       when the estimate was valid; never null
 * @param pose       x, y in metres, theta in radians; never null
 * @param covariance its uncertainty; never null
 */
public record PoseEstimate(Instant time, Pose2D pose, PoseCovariance covariance) {
    public PoseEstimate {
        Objects.requireNonNull(time, "time");
        Objects.requireNonNull(pose, "pose");
        Objects.requireNonNull(covariance, "covariance");
    }

    /**
     * cm.position's covariance: the upper triangle of the 3x3 (x, y, theta) matrix as one row of a SWE
     * {@code DataArray} in the text encoding (one {@code <values>} block instead of six {@code Quantity}s).
     */
    private static final List<DataArray.Column> COVARIANCE_COLUMNS = List.of(DataArray.Column.quantity("xx", "m2"),
            DataArray.Column.quantity("xy", "m2"), DataArray.Column.quantity("xtheta", "m.rad"), DataArray.Column
                    .quantity("yy", "m2"), DataArray.Column.quantity("ytheta", "m.rad"), DataArray.Column.quantity(
                            "thetatheta", "rad2"));

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<PoseEstimate> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(PoseEstimate p) {
            PoseCovariance c = p.covariance();
            return new RecordBuilder().time("time", p.time()).quantity("x", "m", p.pose().x()).quantity("y", "m", p
                    .pose().y()).quantity("theta", "rad", p.pose().theta()).add("covariance", new DataArray(
                            "covariance", COVARIANCE_COLUMNS, List.<double[]>of(new double[] { c.xx(), c.xy(), c
                                    .xTheta(), c.yy(), c.yTheta(), c.thetaTheta() }))).build();
        }

        @Override
        public PoseEstimate decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "time", "x", "y", "theta", "covariance");
            List<double[]> rows = r.array("covariance", COVARIANCE_COLUMNS, Integer.MAX_VALUE);
            if (rows.size() != 1) {
                throw new PayloadException(ControlMlCondition.MALFORMED_PAYLOAD, "covariance must have exactly 1 row"
                        + " (the upper triangle xx,xy,xtheta,yy,ytheta,thetatheta), not " + rows.size());
            }
            double[] c = rows.get(0);
            for (int i : new int[] { 0, 3, 5 }) {
                if (c[i] < 0) {
                    throw new PayloadException(ControlMlCondition.INVALID_VALUE, "covariance."
                            + COVARIANCE_COLUMNS.get(i).name() + " is a variance and must be >= 0, not " + c[i]);
                }
            }
            return new PoseEstimate(r.time("time"), new Pose2D(r.quantity("x", "m"), r.quantity("y", "m"), r.quantity(
                    "theta", "rad")), new PoseCovariance(c[0], c[1], c[2], c[3], c[4], c[5]));
        }
    };
}
