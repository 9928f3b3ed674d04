package sabot.pidstep.controlml;

import java.util.ArrayList;
import java.util.List;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.payload.PayloadCodec;
import sabot.controlml.payload.PayloadException;
import sabot.controlml.payload.RecordBuilder;
import sabot.controlml.payload.RecordReader;
import sabot.controlml.swe.DataArray;
import sabot.controlml.swe.SweComponent;
import sabot.pidstep.StepSample;

/**
 * {@code cm.pid.step}'s value: a position step of one wheel's motor loop and, in the robot's answer, the response the
 * motor board recorded. The request carries no samples.
 *
 * @param motor   the motor, numbered as in {@code cm.pid} (0 left, 1 right on a SabotOne)
 * @param step    m of wheel travel, non-zero; negative steps backwards
 * @param samples the response (t s, set-point m, measured m), in time order; empty in a request; never null
 */
public record StepTest(int motor, double step, List<StepSample> samples) {

    /** Most samples an answer may carry (a SACT board records 256). */
    public static final int MAX_SAMPLES = 1024;
    /** Largest step the protocol carries, m (the robot's own limit is smaller: its board's). */
    public static final double MAX_STEP = 0.1;

    public StepTest {
        samples = List.copyOf(samples);
    }

    /** @return a request: a step of {@code step} metres on {@code motor} */
    public static StepTest request(int motor, double step) {
        return new StepTest(motor, step, List.of());
    }

    private static final List<DataArray.Column> COLUMNS = List.of(DataArray.Column.quantity("t", "s"), DataArray
            .Column.quantity("setpoint", "m"), DataArray.Column.quantity("measured", "m"));

    /**
     * The schema: {@code motor} Count 0..15; {@code step} Quantity m, 0 &lt; |step| &le; {@link #MAX_STEP};
     * {@code samples} DataArray {@code sample} of [{@code t} s &ge; 0, not decreasing; {@code setpoint} m;
     * {@code measured} m], at most {@link #MAX_SAMPLES} rows.
     */
    public static final PayloadCodec<StepTest> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(StepTest s) {
            List<double[]> rows = new ArrayList<>(s.samples().size());
            for (StepSample x : s.samples()) {
                rows.add(new double[] { x.t(), x.setPoint(), x.measured() });
            }
            return new RecordBuilder().count("motor", s.motor()).quantity("step", "m", s.step()).add("samples",
                    new DataArray("sample", COLUMNS, rows)).build();
        }

        @Override
        public StepTest decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "motor", "step", "samples");
            int motor = (int) r.count("motor", 0, 15);
            double step = r.quantity("step", "m", -MAX_STEP, MAX_STEP);
            if (step == 0) {
                throw new PayloadException(ControlMlCondition.INVALID_VALUE, "step must not be 0 m");
            }
            List<StepSample> samples = new ArrayList<>();
            double previous = 0;
            for (double[] row : r.array("samples", COLUMNS, MAX_SAMPLES)) {
                if (row[0] < previous) {
                    throw new PayloadException(ControlMlCondition.INVALID_VALUE,
                            "sample times must start at >= 0 s and not decrease");
                }
                previous = row[0];
                samples.add(new StepSample(row[0], row[1], row[2]));
            }
            return new StepTest(motor, step, samples);
        }
    };
}
