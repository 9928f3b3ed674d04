package sabot.modbus.internal;

import java.io.IOException;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.OptionalDouble;

import sabot.modbus.SonarClient;
import sabot.modbus.SonarReading;
import sabot.modbus.internal.ModbusMap.Field;

/** The sonar board's client: sensor n's records are the map's {@code s<n>_...} records of file {@code latest}. */
final class SonarDriver extends BoardDriver implements SonarClient {

    private static final String BOARD = "sonar";
    private static final String LATEST = "latest";
    private static final String[] RECORDS = { "sequence", "angle", "range", "x", "y", "flags" };
    /**
     * The echo-valid bit of {@code s<n>_flags}: the map describes it ("bit0 echo valid") but gives no {@code bits}
     * object for it, unlike the SACT status record; used only when the map names none.
     */
    private static final int ECHO_VALID_BIT_IF_UNNAMED = 0;

    private final ModbusMap map;
    private final int sensors;
    private final Span all;

    SonarDriver(Bus bus, Bus.Counters counters) {
        super(bus, counters);
        this.map = bus.map();
        int n = 0;
        while (map.has(BOARD, LATEST, "s" + n + "_sequence")) {
            n++;
        }
        sensors = n;
        List<Field> fields = new ArrayList<>();
        for (int s = 0; s < sensors; s++) {
            for (String r : RECORDS) {
                fields.add(f(s, r));
            }
        }
        all = Span.of(fields);
    }

    private Field f(int sensor, String record) {
        return map.field(BOARD, LATEST, "s" + sensor + "_" + record);
    }

    private Span span(int sensor) {
        List<Field> fields = new ArrayList<>();
        for (String r : RECORDS) {
            fields.add(f(sensor, r));
        }
        return Span.of(fields);
    }

    @Override
    public int sensorCount() {
        return sensors;
    }

    @Override
    public SonarReading readSensor(int sensor) throws IOException {
        if (sensor < 0 || sensor >= sensors) {
            throw new IllegalArgumentException("sonar sensor " + sensor + " does not exist (0-" + (sensors - 1) + ")");
        }
        Span span = span(sensor);
        return reading(sensor, span, bus.read(counters, span)[0]);
    }

    @Override
    public List<SonarReading> readSensors() throws IOException {
        short[] r = bus.read(counters, all)[0];
        List<SonarReading> list = new ArrayList<>();
        for (int s = 0; s < sensors; s++) {
            list.add(reading(s, all, r));
        }
        return List.copyOf(list);
    }

    private SonarReading reading(int s, Span span, short[] r) {
        Field flags = f(s, "flags");
        int validBit = flags.bits().getOrDefault("echo_valid", ECHO_VALID_BIT_IF_UNNAMED);
        long range = span.raw(f(s, "range"), r);
        return new SonarReading(s, (int) span.raw(f(s, "sequence"), r), span.si(f(s, "angle"), r),
                range == 0 ? OptionalDouble.empty() : OptionalDouble.of(f(s, "range").si(range)),
                span.si(f(s, "x"), r), span.si(f(s, "y"), r), (span.raw(flags, r) >> validBit & 1) != 0);
    }

    @Override
    public Duration readSensorWireTime() {
        return bus.timing().readTime(span(0).count());
    }

    @Override
    public Duration typicalWireTime() {
        return readSensorWireTime();
    }
}
