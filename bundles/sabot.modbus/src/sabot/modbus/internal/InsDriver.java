package sabot.modbus.internal;

import java.io.IOException;
import java.time.Duration;

import sabot.modbus.InsClient;
import sabot.modbus.InsMotion;
import sabot.modbus.InsSample;
import sabot.modbus.internal.ModbusMap.Field;

/** The inertial board's client. */
final class InsDriver extends BoardDriver implements InsClient {

    private static final String BOARD = "ins";
    private static final String SAMPLE = "sample";

    private final ModbusMap map;
    private final Span full;
    private final Span motion;

    InsDriver(Bus bus, Bus.Counters counters) {
        super(bus, counters);
        this.map = bus.map();
        full = Span.of(map.file(BOARD, SAMPLE));
        motion = Span.of(f("gyro_z"), f("accel_x"));
    }

    private Field f(String record) {
        return map.field(BOARD, SAMPLE, record);
    }

    @Override
    public InsSample read() throws IOException {
        short[] r = bus.read(counters, full)[0];
        return new InsSample((int) full.raw(f("sample_counter"), r), full.si(f("gyro_x"), r),
                full.si(f("gyro_y"), r), full.si(f("gyro_z"), r), full.si(f("accel_x"), r),
                full.si(f("accel_y"), r), full.si(f("accel_z"), r), full.si(f("mag_x"), r), full.si(f("mag_y"), r),
                full.si(f("mag_z"), r), temperature(full.raw(f("temperature"), r)));
    }

    /** The map's scale gives degrees above the sensor's 21 °C offset (MPU-9250: 333.87 LSB/°C above 21 °C). */
    private double temperature(long raw) {
        return f("temperature").si(raw) + 21.0;
    }

    @Override
    public InsMotion readMotion() throws IOException {
        short[] r = bus.read(counters, motion)[0];
        return new InsMotion(motion.si(f("gyro_z"), r), motion.si(f("accel_x"), r));
    }

    @Override
    public Duration readWireTime() {
        return bus.timing().readTime(full.count());
    }

    @Override
    public Duration readMotionWireTime() {
        return bus.timing().readTime(motion.count());
    }

    @Override
    public Duration typicalWireTime() {
        return readMotionWireTime();
    }
}
