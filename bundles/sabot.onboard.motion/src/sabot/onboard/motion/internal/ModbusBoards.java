package sabot.onboard.motion.internal;

import java.io.IOException;
import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;

import sabot.controlml.payload.MotorGains;
import sabot.controlml.payload.PidGains;
import sabot.model.geometry.Point2D;
import sabot.model.robot.BatteryState;
import sabot.modbus.Board;
import sabot.modbus.BoardException;
import sabot.modbus.InsMotion;
import sabot.modbus.LandmarkSighting;
import sabot.modbus.PowerReading;
import sabot.modbus.ModbusBus;
import sabot.modbus.Motor;
import sabot.modbus.SactGains;
import sabot.modbus.SactConfig;
import sabot.modbus.SonarReading;
import sabot.modbus.StepCapture;
import sabot.modbus.WheelCounts;
import sabot.modbus.WheelState;
import sabot.modbus.Wheels;
import sabot.onboard.motion.loop.RobotBoards;
import sabot.onboard.motion.loop.SonarPing;

/** {@link RobotBoards} over the three board clients of one Modbus bus. */
final class ModbusBoards implements RobotBoards {

    /** cm.pid motor index → SACT motor file: 0 left, 1 right (docs/CONTROLML.md §4). */
    private static final Motor[] MOTORS = { Motor.LEFT, Motor.RIGHT };
    /** The SACT gain registers are uint16 limited to 0..32767 (docs/SACT-MODBUS.md, files 1 and 2). */
    private static final int MAX_GAIN = 32767;
    /**
     * Control periods per sample of a step test: 8 x 50 us = 0.4 ms, so the board's 256 samples span 102 ms, three
     * times the settling of the default gains (test_control.c: 30 ms for 200 counts) and 50 samples in the rise.
     */
    static final int STEP_DECIMATION = 8;
    /** How long past the recording's length a step test waits for the board to finish it. */
    private static final Duration STEP_GRACE = Duration.ofSeconds(1);

    private final ModbusBus bus;
    /** The battery's design capacity, Ah, read from the power board once; 0 until then. Loop thread only. */
    private double designCapacity;
    /** Where each sonar sensor sits on the robot, learnt from its echoes; loop thread only. */
    private final Map<Integer, Point2D> sonarOrigins = new HashMap<>();

    ModbusBoards(ModbusBus bus) {
        this.bus = bus;
    }

    @Override
    public WheelCounts readEncoders() throws IOException {
        return bus.sact().readPositions();
    }

    @Override
    public void writeWheelSpeeds(double left, double right) throws IOException {
        try {
            bus.sact().setWheelSpeeds(left, right);
        } catch (BoardException e) {
            if (e.isServerDeviceFailure()) {
                throw new MotorFaultException(latchedFaults(), e);
            }
            throw e;
        }
    }

    /** @return which motors have a latched fault and why, e.g. "left motor fault: following error (...)" */
    private String latchedFaults() {
        Wheels w;
        try {
            w = bus.sact().readWheels();
        } catch (IOException e) {
            return "motor fault latched (the motor board refuses set-points; its status could not be read: "
                    + e.getMessage() + ")";
        }
        List<String> faults = new ArrayList<>();
        describe("left", w.left(), faults);
        describe("right", w.right(), faults);
        return faults.isEmpty() ? "motor board refuses set-points (server device failure) without a latched fault"
                : String.join(", ", faults);
    }

    private static void describe(String motor, WheelState s, List<String> out) {
        if (!s.faultLatched()) {
            return;
        }
        List<String> causes = new ArrayList<>();
        if (s.followingError()) {
            causes.add("following error (the wheel does not turn as commanded: jammed or stalled?)");
        }
        if (s.overCurrent()) {
            causes.add("over-current");
        }
        out.add(motor + " motor fault: " + (causes.isEmpty() ? "latched" : String.join(" and ", causes)));
    }

    @Override
    public ImuSample readImu() throws IOException {
        InsMotion m = bus.ins().readMotion();
        return new ImuSample(m.gyroZ(), m.accelX());
    }

    @Override
    public LandmarkSighting readLandmark() throws IOException {
        return bus.landmark().readLatest();
    }

    @Override
    public boolean landmarkBoardFaulted() {
        return bus.landmark().faulted();
    }

    @Override
    public BatteryState readBattery(Instant now) throws IOException {
        double capacity = designCapacity;
        if (capacity == 0) {
            capacity = bus.power().readConfig().designCapacity();
            designCapacity = capacity;
        }
        PowerReading r = bus.power().readLatest();
        try {
            return new BatteryState(now, r.stateOfCharge(), r.voltage(), r.current(), capacity, r.docked(),
                    r.charging(), r.full());
        } catch (IllegalArgumentException e) {
            throw new BoardException("power", BoardException.Kind.IMPLAUSIBLE, 0, e.getMessage());
        }
    }

    @Override
    public boolean powerBoardFaulted() {
        return bus.power().faulted();
    }

    @Override
    public int sonarSensors() {
        return bus.sonar().sensorCount();
    }

    /**
     * The board reports the echo's position and range, not the sensor's: the sensor sits at the echo minus the range
     * along the axis (its servo turns it in place), remembered per sensor for the pings that hear nothing.
     */
    @Override
    public Optional<SonarPing> readSonar(int sensor) throws IOException {
        SonarReading r = bus.sonar().readSensor(sensor);
        if (r.valid() && r.range().isPresent()) {
            double range = r.range().getAsDouble();
            Point2D origin = new Point2D(r.x() - range * Math.cos(r.angle()), r.y() - range * Math.sin(r.angle()));
            sonarOrigins.put(sensor, origin);
            return Optional.of(new SonarPing(origin, r.angle(), range, true));
        }
        Point2D origin = sonarOrigins.get(sensor);
        return origin == null ? Optional.empty() : Optional.of(SonarPing.silence(origin, r.angle()));
    }

    @Override
    public void brake(boolean on) throws IOException {
        bus.sact().brake(on);
    }

    @Override
    public void acknowledgeFaults() throws IOException {
        bus.sact().acknowledgeFaults();
    }

    @Override
    public void setBoardDeadman(Duration timeout) throws IOException {
        bus.sact().setCommandTimeout(timeout);
    }

    @Override
    public void writeLimits(double maxWheelSpeed, double maxWheelAcceleration) throws IOException {
        bus.sact().writeLimits(maxWheelSpeed, maxWheelAcceleration);
    }

    @Override
    public PidGains readGains() throws IOException {
        List<MotorGains> motors = new ArrayList<>();
        for (int i = 0; i < MOTORS.length; i++) {
            SactGains g = bus.sact().readGains(MOTORS[i]);
            motors.add(new MotorGains(i, g.kp(), g.ki(), g.kd()));
        }
        return new PidGains(motors);
    }

    @Override
    public PidGains writeGains(PidGains gains) throws IOException {
        // every value is checked before the first write, so a bad one changes nothing
        SactGains[] next = new SactGains[MOTORS.length];
        for (MotorGains m : gains.motors()) {
            if (m.motor() < 0 || m.motor() >= MOTORS.length) {
                throw new IllegalArgumentException("motor " + m.motor() + ": this robot has motors 0 (left) and 1 "
                        + "(right)");
            }
            SactGains current = bus.sact().readGains(MOTORS[m.motor()]);
            next[m.motor()] = new SactGains(gain("kp", m.motor(), m.kp()), gain("ki", m.motor(), m.ki()),
                    gain("kd", m.motor(), m.kd()), current.integralLimit());
        }
        for (int i = 0; i < MOTORS.length; i++) {
            if (next[i] != null) {
                bus.sact().writeGains(MOTORS[i], next[i]);
            }
        }
        return readGains();
    }

    @Override
    public StepRecording stepTest(int motor, double step) throws IOException {
        if (motor < 0 || motor >= MOTORS.length) {
            throw new IllegalArgumentException("motor " + motor + ": this robot has motors 0 (left) and 1 (right)");
        }
        SactConfig c = bus.sact().config();
        double countsPerMetre = c.countsPerMetre();
        double requested = step * countsPerMetre;
        if (!(Math.abs(requested) >= 0.5)) {
            throw new IllegalArgumentException("a step of " + step + " m is less than one encoder count (" + 1
                    / countsPerMetre + " m)");
        }
        // bounded before the int cast: the board's bound (checked with the map) is far smaller
        int counts = (int) Math.max(-Integer.MAX_VALUE, Math.min(Integer.MAX_VALUE, Math.round(requested)));
        bus.sact().brake(false);
        try {
            bus.sact().startStepCapture(MOTORS[motor], counts, STEP_DECIMATION);
            StepCapture capture = bus.sact().readStepCapture();
            // The board records in real time: wait out the recording's length (a physical duration, not a guess at
            // another thread's progress), then read until it is complete or the grace time is over.
            Duration length = capture.samplePeriod().multipliedBy(capture.capacity());
            java.util.concurrent.locks.LockSupport.parkNanos(length.toNanos());
            long deadline = System.nanoTime() + STEP_GRACE.toNanos();
            capture = bus.sact().readStepCapture();
            while (!capture.complete() && System.nanoTime() < deadline) {
                java.util.concurrent.locks.LockSupport.parkNanos(capture.samplePeriod().multipliedBy(capture
                        .capacity() - capture.counts().length).toNanos());
                capture = bus.sact().readStepCapture();
            }
            if (!capture.complete()) {
                throw new IOException("the motor board recorded " + capture.counts().length + " of " + capture
                        .capacity() + " samples within " + length.plus(STEP_GRACE).toMillis() + " ms");
            }
            double[] measured = new double[capture.counts().length];
            for (int i = 0; i < measured.length; i++) {
                measured[i] = capture.counts()[i] / countsPerMetre;
            }
            return new StepRecording(counts / countsPerMetre, capture.samplePeriod().toNanos() * 1e-9, measured);
        } finally {
            bus.sact().brake(true);
        }
    }

    private static int gain(String name, int motor, double value) {
        if (!(value >= 0 && value <= MAX_GAIN) || value != Math.rint(value)) {
            throw new IllegalArgumentException(name + " of motor " + motor + " must be a whole number 0.." + MAX_GAIN
                    + " (SACT board units), was " + value);
        }
        return (int) value;
    }

    @Override
    public String faultedBoard() {
        for (Board b : new Board[] { bus.sact(), bus.ins(), bus.sonar() }) {
            if (b.faulted()) {
                return b.counters().board();
            }
        }
        return null;
    }

    @Override
    public boolean motorBoardSilentFor(double seconds) {
        Instant last = bus.sact().counters().lastGoodAnswer();
        return last == null || last.isBefore(Instant.now().minusNanos(Math.round(seconds * 1e9)));
    }

    @Override
    public double interFrameDelay() {
        return bus.settings().interFrameDelay().toNanos() * 1e-9;
    }

    @Override
    public double encoderReadWireTime() {
        return bus.sact().readPositionsWireTime().toNanos() * 1e-9;
    }

    @Override
    public double wheelWriteWireTime() {
        return bus.sact().setWheelSpeedsWireTime().toNanos() * 1e-9;
    }

    @Override
    public double optionalReadWireTime() {
        return Math.max(Math.max(bus.ins().readMotionWireTime().toNanos(), bus.sonar().readSensorWireTime().toNanos()),
                Math.max(bus.landmark().readLatestWireTime().toNanos(), bus.power().readLatestWireTime().toNanos()))
                * 1e-9;
    }
}
