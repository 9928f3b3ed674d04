package sabot.modbus.internal;

import java.io.IOException;
import java.time.Duration;
import java.util.Objects;

import sabot.modbus.LandmarkClient;
import sabot.modbus.LandmarkConfig;
import sabot.modbus.LandmarkSighting;
import sabot.modbus.internal.ModbusMap.Field;

/** The ceiling-landmark board's client: file {@code latest} (the measurement) and file {@code config}. */
final class LandmarkDriver extends BoardDriver implements LandmarkClient {

    private static final String BOARD = "landmark";
    private static final String LATEST = "latest";
    private static final String CONFIG = "config";

    private final ModbusMap map;
    private final Span latest;
    private final Span config;

    LandmarkDriver(Bus bus, Bus.Counters counters) {
        super(bus, counters);
        this.map = bus.map();
        latest = Span.of(f(LATEST, "sequence"), f(LATEST, "landmark_id"), f(LATEST, "range"), f(LATEST, "bearing"),
                f(LATEST, "age"));
        config = Span.of(f(CONFIG, "view_radius"), f(CONFIG, "period"));
    }

    private Field f(String file, String record) {
        return map.field(BOARD, file, record);
    }

    @Override
    public LandmarkSighting readLatest() throws IOException {
        short[] r = bus.read(counters, latest)[0];
        return new LandmarkSighting((int) latest.raw(f(LATEST, "sequence"), r),
                (int) latest.raw(f(LATEST, "landmark_id"), r), latest.si(f(LATEST, "range"), r),
                latest.si(f(LATEST, "bearing"), r), duration(latest.si(f(LATEST, "age"), r)));
    }

    @Override
    public LandmarkConfig readConfig() throws IOException {
        short[] r = bus.read(counters, config)[0];
        return new LandmarkConfig(config.si(f(CONFIG, "view_radius"), r),
                duration(config.si(f(CONFIG, "period"), r)));
    }

    /** The map's seconds as a Duration, to the nanosecond (the registers count whole milliseconds). */
    private static Duration duration(double seconds) {
        return Duration.ofNanos(Math.round(seconds * 1e9));
    }

    @Override
    public void writeConfig(LandmarkConfig c) throws IOException {
        Objects.requireNonNull(c, "config");
        if (c.period() == null) {
            throw new IllegalArgumentException("landmark period is null");
        }
        Field radius = f(CONFIG, "view_radius");
        Field period = f(CONFIG, "period");
        long r = radius.raw("landmark view radius", c.viewRadius());
        long p = period.raw("landmark period", c.period().toNanos() / 1e9);
        if (period.record() == radius.record() + 1) {
            bus.write(counters, new Bus.Write(radius.file(), radius.record(), new short[] { (short) r, (short) p }));
        } else {
            bus.write(counters, new Bus.Write(radius.file(), radius.record(), radius.encode(r)),
                    new Bus.Write(period.file(), period.record(), period.encode(p)));
        }
    }

    @Override
    public Duration readLatestWireTime() {
        return bus.timing().readTime(latest.count());
    }

    @Override
    public Duration typicalWireTime() {
        return readLatestWireTime();
    }
}
