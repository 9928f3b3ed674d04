package sabot.modbus.internal;

import java.io.IOException;
import java.time.Duration;
import java.util.List;

import sabot.modbus.BoardException;
import sabot.modbus.Motor;
import sabot.modbus.SactGains;
import sabot.modbus.SactClient;
import sabot.modbus.SactConfig;
import sabot.modbus.StepCapture;
import sabot.modbus.WheelCounts;
import sabot.modbus.WheelState;
import sabot.modbus.Wheels;
import sabot.modbus.internal.ModbusMap.Field;

/** The SACT board's client: every record looked up by name in the register map. */
final class SactDriver extends BoardDriver implements SactClient {

    private static final String BOARD = "sact";
    private static final String CONFIG = "config";
    private static final String DRIVE = "drive";

    private final ModbusMap map;
    private final Field driveLeft;
    private final Field driveRight;
    private final Span configSpan;
    private final Span wheelSpanLeft;
    private final Span wheelSpanRight;
    private final Span positionSpanLeft;
    private final Span positionSpanRight;
    private final Span gainSpan;
    private volatile SactConfig config;

    SactDriver(Bus bus, Bus.Counters counters) {
        super(bus, counters);
        this.map = bus.map();
        driveLeft = map.field(BOARD, DRIVE, "velocity_setpoint_left");
        driveRight = map.field(BOARD, DRIVE, "velocity_setpoint_right");
        if (driveRight.record() != driveLeft.record() + 1) {
            throw new IllegalStateException("the map's drive set-points are not adjacent: one sub-request needs them so");
        }
        configSpan = Span.of(map.file(BOARD, CONFIG));
        wheelSpanLeft = wheelSpan(Motor.LEFT);
        wheelSpanRight = wheelSpan(Motor.RIGHT);
        positionSpanLeft = Span.of(motor(Motor.LEFT, "position"));
        positionSpanRight = Span.of(motor(Motor.RIGHT, "position"));
        gainSpan = Span.of(motor(Motor.LEFT, "kp"), motor(Motor.LEFT, "ki"), motor(Motor.LEFT, "kd"),
                motor(Motor.LEFT, "integral_limit"));
    }

    private Span wheelSpan(Motor m) {
        return Span.of(motor(m, "position"), motor(m, "measured_velocity"), motor(m, "current"), motor(m, "status"));
    }

    private Field motor(Motor m, String record) {
        return map.field(BOARD, m.mapFile(), record);
    }

    private Field config(String record) {
        return map.field(BOARD, CONFIG, record);
    }

    @Override
    public SactConfig config() throws IOException {
        SactConfig c = config;
        return c != null ? c : readConfig();
    }

    private SactConfig readConfig() throws BoardException {
        short[] r = bus.read(counters, configSpan)[0];
        SactConfig c = new SactConfig((int) configSpan.raw(config("encoder_lines"), r),
                configSpan.si(config("gear_ratio"), r), configSpan.si(config("no_load_speed"), r),
                configSpan.si(config("wheel_radius"), r), configSpan.si(config("max_speed"), r),
                configSpan.si(config("max_accel"), r),
                seconds(configSpan.si(config("control_period"), r)),
                (int) configSpan.raw(config("firmware_version"), r),
                seconds(configSpan.si(config("command_timeout"), r)), map.quadrature());
        config = c;
        return c;
    }

    private static Duration seconds(double s) {
        return Duration.ofNanos(Math.round(s * 1e9));
    }

    /** @return the set-point register value of a wheel speed: rad/s → counts/s → LSB (8.8 counts per Ts) */
    private long setpoint(String which, double radPerS, SactConfig c) {
        if (!Double.isFinite(radPerS)) {
            throw new IllegalArgumentException(which + " wheel speed is " + radPerS + " rad/s");
        }
        long raw = Math.round(radPerS * c.countsPerWheelRadian() / driveLeft.scale());
        driveLeft.checkBounds(which + " wheel speed " + radPerS + " rad/s", raw);
        return raw;
    }

    @Override
    public void setWheelSpeeds(double leftRadPerS, double rightRadPerS) throws IOException {
        SactConfig c = config();
        long l = setpoint("left", leftRadPerS, c);
        long r = setpoint("right", rightRadPerS, c);
        bus.write(counters, new Bus.Write(driveLeft.file(), driveLeft.record(), new short[] { (short) l, (short) r }));
    }

    @Override
    public Wheels readWheels() throws IOException {
        SactConfig c = config();
        short[][] r = bus.read(counters, wheelSpanLeft, wheelSpanRight);
        return new Wheels(wheel(Motor.LEFT, wheelSpanLeft, r[0], c), wheel(Motor.RIGHT, wheelSpanRight, r[1], c));
    }

    @Override
    public WheelCounts readPositions() throws IOException {
        short[][] r = bus.read(counters, positionSpanLeft, positionSpanRight);
        return new WheelCounts((int) positionSpanLeft.raw(motor(Motor.LEFT, "position"), r[0]),
                (int) positionSpanRight.raw(motor(Motor.RIGHT, "position"), r[1]));
    }

    @Override
    public Duration readPositionsWireTime() {
        return bus.timing().readTime(positionSpanLeft.count(), positionSpanRight.count());
    }

    private WheelState wheel(Motor m, Span span, short[] regs, SactConfig c) {
        Field status = motor(m, "status");
        long flags = span.raw(status, regs);
        return new WheelState((int) span.raw(motor(m, "position"), regs),
                span.si(motor(m, "measured_velocity"), regs) / c.countsPerWheelRadian(),
                span.si(motor(m, "current"), regs),
                bit(flags, status, "fault"), bit(flags, status, "over_current"),
                bit(flags, status, "following_error"), bit(flags, status, "braking"),
                bit(flags, status, "at_setpoint"));
    }

    private static boolean bit(long flags, Field f, String name) {
        return (flags >> f.bit(name) & 1) != 0;
    }

    @Override
    public void brake(boolean on) throws IOException {
        Field left = motor(Motor.LEFT, "brake");
        Field right = motor(Motor.RIGHT, "brake");
        short v = (short) (on ? 1 : 0);
        left.checkBounds("brake", v);
        Bus.Write l = new Bus.Write(left.file(), left.record(), new short[] { v });
        Bus.Write r = new Bus.Write(right.file(), right.record(), new short[] { v });
        if (on) {
            // set-points to zero in the same request: the board validates all before it changes any
            bus.write(counters, new Bus.Write(driveLeft.file(), driveLeft.record(), new short[] { 0, 0 }), l, r);
        } else {
            bus.write(counters, l, r);
        }
    }

    @Override
    public SactGains readGains(Motor motor) throws IOException {
        short[] r = bus.read(counters, new Span(motor(motor, "kp").file(), gainSpan.record(), gainSpan.count()))[0];
        return new SactGains((int) gainSpan.raw(motor(motor, "kp"), r), (int) gainSpan.raw(motor(motor, "ki"), r),
                (int) gainSpan.raw(motor(motor, "kd"), r), (int) gainSpan.raw(motor(motor, "integral_limit"), r));
    }

    @Override
    public void writeGains(Motor motor, SactGains g) throws IOException {
        List<Field> fields = List.of(motor(motor, "kp"), motor(motor, "ki"), motor(motor, "kd"),
                motor(motor, "integral_limit"));
        long[] values = { g.kp(), g.ki(), g.kd(), g.integralLimit() };
        short[] regs = new short[gainSpan.count()];
        for (int i = 0; i < fields.size(); i++) {
            fields.get(i).checkBounds(motor + " " + fields.get(i).name(), values[i]);
            regs[fields.get(i).record() - gainSpan.record()] = (short) values[i];
        }
        bus.write(counters, new Bus.Write(fields.get(0).file(), gainSpan.record(), regs));
    }

    @Override
    public void writeLimits(double maxSpeed, double maxAccel) throws IOException {
        Field speed = config("max_speed");
        Field accel = config("max_accel");
        long s = raw(speed, "maxSpeed", maxSpeed);
        long a = raw(accel, "maxAccel", maxAccel);
        if (accel.record() == speed.record() + 1) {
            bus.write(counters, new Bus.Write(speed.file(), speed.record(), new short[] { (short) s, (short) a }));
        } else {
            bus.write(counters, new Bus.Write(speed.file(), speed.record(), speed.encode(s)),
                    new Bus.Write(accel.file(), accel.record(), accel.encode(a)));
        }
        readConfig();
    }

    private static long raw(Field f, String what, double si) {
        return f.raw(what, si);
    }

    @Override
    public void setCommandTimeout(Duration timeout) throws IOException {
        Field f = config("command_timeout");
        if (timeout == null || timeout.isNegative()) {
            throw new IllegalArgumentException("command timeout " + timeout);
        }
        long raw = raw(f, "command timeout", timeout.toNanos() / 1e9);
        bus.write(counters, new Bus.Write(f.file(), f.record(), f.encode(raw)));
        readConfig();
    }

    @Override
    public void acknowledgeFaults() throws IOException {
        Field l = motor(Motor.LEFT, "status");
        Field r = motor(Motor.RIGHT, "status");
        bus.write(counters, new Bus.Write(l.file(), l.record(), l.encode(0)),
                new Bus.Write(r.file(), r.record(), r.encode(0)));
    }

    @Override
    public void positionStep(Motor motor, int counts) throws IOException {
        Field f = motor(motor, "position_step");
        f.checkBounds(motor + " position step", counts);
        writeOnce(new Bus.Write(f.file(), f.record(), f.encode(counts)));
    }

    /** The idempotency key of the last non-idempotent write; -1 until read from the board. */
    private int lastKey = -1;

    /**
     * Writes a request that must never be applied twice (a step adds to a position): keyed with the board's
     * {@code command_sequence} as its first register, so that a retry after a lost answer — the same request, the same
     * key — is answered by the board but not applied again. Keys run 1…65535 and round again; the first one follows
     * the board's last key, so a restarted master does not reuse it.
     */
    private synchronized void writeOnce(Bus.Write write) throws IOException {
        Field key = config("command_sequence");
        if (lastKey < 0) {
            Span s = Span.of(key);
            lastKey = (int) s.raw(key, bus.read(counters, s)[0]);
        }
        lastKey = lastKey % 65535 + 1;
        bus.write(counters, new Bus.Write(key.file(), key.record(), key.encode(lastKey)), write);
    }

    private static final String CAPTURE = "step_capture";
    /** Registers per read of the recording: 120 × 2 bytes + headers fit one 253-byte PDU. */
    private static final int CAPTURE_CHUNK = 120;

    @Override
    public void startStepCapture(Motor motor, int counts, int decimation) throws IOException {
        Field which = map.field(BOARD, CAPTURE, "motor");
        Field every = map.field(BOARD, CAPTURE, "decimation");
        Field step = map.field(BOARD, CAPTURE, "step");
        int file = motor(motor, "kp").file();
        step.checkBounds(motor + " position step", counts);
        every.checkBounds("capture decimation", decimation);
        which.checkBounds("capture motor", file);
        Field following = motor(motor, "following_error_limit");
        Span f = Span.of(following);
        long limit = f.raw(following, bus.read(counters, f)[0]);
        if (Math.abs(counts) >= limit) {
            throw new IllegalArgumentException(motor + " position step of " + counts + " counts would trip the "
                    + "motor's following-error limit (" + limit + " counts): the board would brake and latch a fault");
        }
        // the step in a request of its own: the board validates a request before applying any of it, and judges the
        // step against the motor in force
        bus.write(counters, new Bus.Write(which.file(), which.record(), which.encode(file)), new Bus.Write(every
                .file(), every.record(), every.encode(decimation)));
        writeOnce(new Bus.Write(step.file(), step.record(), step.encode(counts)));
    }

    @Override
    public StepCapture readStepCapture() throws IOException {
        Span head = Span.of(map.field(BOARD, CAPTURE, "motor"), map.field(BOARD, CAPTURE, "decimation"), map.field(
                BOARD, CAPTURE, "recorded"));
        short[] h = bus.read(counters, head)[0];
        Field recordedField = map.field(BOARD, CAPTURE, "recorded");
        int recorded = (int) head.raw(recordedField, h);
        Motor motor = head.raw(map.field(BOARD, CAPTURE, "motor"), h) == motor(Motor.LEFT, "kp").file() ? Motor.LEFT
                : Motor.RIGHT;
        Duration period = seconds(head.si(map.field(BOARD, CAPTURE, "decimation"), h));
        Field response = map.field(BOARD, CAPTURE, "response");
        int[] counts = new int[Math.min(recorded, response.count())];
        for (int from = 0; from < counts.length; from += CAPTURE_CHUNK) {
            int n = Math.min(CAPTURE_CHUNK, counts.length - from);
            short[] r = bus.read(counters, new Span(response.file(), response.record() + from, n))[0];
            for (int i = 0; i < n; i++) {
                counts[from + i] = r[i];
            }
        }
        return new StepCapture(motor, period, counts, (int) recordedField.max());
    }

    @Override
    public Duration readWheelsWireTime() {
        return bus.timing().readTime(wheelSpanLeft.count(), wheelSpanRight.count());
    }

    @Override
    public Duration setWheelSpeedsWireTime() {
        return bus.timing().writeTime(2);
    }

    @Override
    public Duration typicalWireTime() {
        return readWheelsWireTime();
    }
}
