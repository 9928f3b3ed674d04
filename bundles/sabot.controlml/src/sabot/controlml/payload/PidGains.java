package sabot.controlml.payload;

import java.util.ArrayList;
import java.util.List;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.swe.DataArray;
import sabot.controlml.swe.SweComponent;

/** {@code cm.pid}: gains per motor, motors unique. @param motors the gains; never null */
public record PidGains(List<MotorGains> motors) {
    public PidGains {
        motors = List.copyOf(motors);
    }

    private static final List<DataArray.Column> GAIN_COLUMNS = List.of(DataArray.Column.count("motor"), DataArray
            .Column.quantity("kp", "1"), DataArray.Column.quantity("ki", "1"), DataArray.Column.quantity("kd", "1"));

    /** The payload schema (section 4 of {@code docs/CONTROLML.md}): fields, SWE types, canonical units, ranges. */
    public static final PayloadCodec<PidGains> CODEC = new PayloadCodec<>() {
        @Override
        public SweComponent encode(PidGains g) {
            List<double[]> rows = new ArrayList<>();
            for (MotorGains m : g.motors()) {
                rows.add(new double[] { m.motor(), m.kp(), m.ki(), m.kd() });
            }
            return new RecordBuilder().add("gains", new DataArray("motor", GAIN_COLUMNS, rows)).build();
        }

        @Override
        public PidGains decode(SweComponent payload) throws PayloadException {
            RecordReader r = RecordReader.of(payload, "gains");
            List<MotorGains> motors = new ArrayList<>();
            long seen = 0;
            for (double[] row : r.array("gains", GAIN_COLUMNS, 16)) {
                int motor = (int) row[0];
                if (row[0] < 0 || row[0] > 15 || (seen & (1L << motor)) != 0) {
                    throw new PayloadException(ControlMlCondition.INVALID_VALUE, "motor indexes must be unique, 0..15");
                }
                seen |= 1L << motor;
                if (row[1] < 0 || row[2] < 0 || row[3] < 0) {
                    throw new PayloadException(ControlMlCondition.INVALID_VALUE, "PID gains must be >= 0");
                }
                motors.add(new MotorGains(motor, row[1], row[2], row[3]));
            }
            if (motors.isEmpty()) {
                throw new PayloadException(ControlMlCondition.INVALID_VALUE, "gains of at least one motor");
            }
            return new PidGains(motors);
        }
    };
}
