package sabot.modbus.internal;

import java.io.IOException;
import java.time.Duration;

import sabot.modbus.BoardException;
import sabot.modbus.PowerClient;
import sabot.modbus.PowerConfig;
import sabot.modbus.PowerReading;
import sabot.modbus.internal.ModbusMap.Field;

/**
 * The power board's client: file {@code latest} (the measurement) and file {@code config}. A value outside the map's
 * bounds, or a status bit the map does not name, is refused as {@link BoardException.Kind#IMPLAUSIBLE}: a gauge that
 * reports 120 % must not be believed.
 */
final class PowerDriver extends BoardDriver implements PowerClient {

    private static final String BOARD = "power";
    private static final String LATEST = "latest";
    private static final String CONFIG = "config";

    private final ModbusMap map;
    private final Span latest;
    private final Span config;
    private final Field sequence;
    private final Field voltage;
    private final Field current;
    private final Field stateOfCharge;
    private final Field status;
    /** The status bits the map names. */
    private final long knownBits;

    PowerDriver(Bus bus, Bus.Counters counters) {
        super(bus, counters);
        this.map = bus.map();
        sequence = f(LATEST, "sequence");
        voltage = f(LATEST, "voltage");
        current = f(LATEST, "current");
        stateOfCharge = f(LATEST, "state_of_charge");
        status = f(LATEST, "status");
        latest = Span.of(sequence, voltage, current, stateOfCharge, status);
        config = Span.of(f(CONFIG, "design_capacity"), f(CONFIG, "period"));
        long bits = 0;
        for (String flag : new String[] { "docked", "charging", "full" }) {
            bits |= 1L << status.bit(flag);
        }
        knownBits = bits;
    }

    private Field f(String file, String record) {
        return map.field(BOARD, file, record);
    }

    @Override
    public PowerReading readLatest() throws IOException {
        short[] r = bus.read(counters, latest)[0];
        long flags = latest.raw(status, r);
        if ((flags & ~knownBits) != 0) {
            throw implausible(String.format("status 0x%04x sets bits the register map does not name (0x%04x)", flags,
                    flags & ~knownBits));
        }
        return new PowerReading((int) latest.raw(sequence, r), voltage.si(checked(voltage, latest.raw(voltage, r))),
                current.si(checked(current, latest.raw(current, r))),
                stateOfCharge.si(checked(stateOfCharge, latest.raw(stateOfCharge, r))), set(flags, "docked"),
                set(flags, "charging"), set(flags, "full"));
    }

    private boolean set(long flags, String flag) {
        return (flags >> status.bit(flag) & 1) != 0;
    }

    private long checked(Field f, long raw) throws BoardException {
        if (raw < f.min() || raw > f.max()) {
            throw implausible(String.format("%s %d is outside the register map's bounds [%d, %d]", f.name(), raw,
                    f.min(), f.max()));
        }
        return raw;
    }

    private BoardException implausible(String what) {
        return new BoardException(BOARD, BoardException.Kind.IMPLAUSIBLE, 0, what);
    }

    @Override
    public PowerConfig readConfig() throws IOException {
        Field capacity = f(CONFIG, "design_capacity");
        Field period = f(CONFIG, "period");
        short[] r = bus.read(counters, config)[0];
        return new PowerConfig(capacity.si(checked(capacity, config.raw(capacity, r))),
                Duration.ofMillis(Math.round(period.si(config.raw(period, r)) * 1000)));
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
