package sabot.onboard.motion.loop;

import java.io.IOException;
import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.Optional;

import sabot.controlml.payload.PidGains;
import sabot.model.geometry.Point2D;
import sabot.model.robot.BatteryState;
import sabot.model.robot.RobotDescription;
import sabot.modbus.LandmarkSighting;
import sabot.modbus.WheelCounts;

/**
 * The robot's boards as a test sees them: records every wheel write and brake command, and answers the encoder read
 * with the counts of ideal wheels that turn at the last set-point written (integrated on the fake clock), unless the
 * robot is held ({@link #stuck}). A motor fault can be latched; the sonar answers with scripted echoes.
 */
final class FakeBoards implements RobotBoards {

    /** One wheel write: when (s on the fake clock) and the set-points, rad/s at the wheel. */
    record WheelWrite(double time, double left, double right) {
    }

    private final ManualClock clock;
    private final RobotDescription robot;
    final List<WheelWrite> writes = new ArrayList<>();
    /** Brake commands in order: true applied, false released. */
    final List<Boolean> brakes = new ArrayList<>();
    /** The motor board refuses set-points (a latched motor fault) until the faults are acknowledged. */
    boolean motorFault;
    /** The wheels do not turn whatever they are told (the robot is held). */
    boolean stuck;
    /** What the sonar sensor sees, robot frame, m. */
    List<Point2D> echoes = List.of();
    private boolean braked;
    private double left;
    private double right;
    /** Wheel angles, rad, and when they were last integrated, s. */
    private double leftAngle;
    private double rightAngle;
    private double integratedTo;

    FakeBoards(ManualClock clock, RobotDescription robot) {
        this.clock = clock;
        this.robot = robot;
    }

    private void integrate() {
        double t = clock.seconds();
        if (!stuck && !braked) {
            leftAngle += left * (t - integratedTo);
            rightAngle += right * (t - integratedTo);
        }
        integratedTo = t;
    }

    WheelWrite lastWrite() {
        return writes.get(writes.size() - 1);
    }

    boolean braked() {
        return braked;
    }

    @Override
    public WheelCounts readEncoders() {
        integrate();
        double perRad = robot.countsPerWheelRevolution() / (2 * Math.PI);
        return new WheelCounts((int) Math.round(leftAngle * perRad), (int) Math.round(rightAngle * perRad));
    }

    @Override
    public void writeWheelSpeeds(double l, double r) throws IOException {
        if (motorFault) {
            throw new MotorFaultException("left motor fault: following error", null);
        }
        integrate();
        writes.add(new WheelWrite(clock.seconds(), l, r));
        left = l;
        right = r;
    }

    @Override
    public ImuSample readImu() {
        return new ImuSample(robot.wheelRadius() * (right - left) / robot.trackWidth(), 0);
    }

    @Override
    public LandmarkSighting readLandmark() {
        return new LandmarkSighting(0, 0, 0, 0, Duration.ZERO);
    }

    @Override
    public boolean landmarkBoardFaulted() {
        return false;
    }

    /** The power board's next answer: a state of charge, or a failure (a test sets it). */
    double batteryCharge = 0.8;
    IOException batteryFailure;
    int batteryReads;
    /** Like the bus's fault time: a board is faulted once a read of it failed, until one succeeds. */
    private boolean batteryReadFailed;

    @Override
    public BatteryState readBattery(Instant now) throws IOException {
        batteryReads++;
        batteryReadFailed = batteryFailure != null;
        if (batteryFailure != null) {
            throw batteryFailure;
        }
        return new BatteryState(now, batteryCharge, 25.0, 0.6, 10.0, false, false, false);
    }

    @Override
    public boolean powerBoardFaulted() {
        return batteryReadFailed;
    }

    @Override
    public int sonarSensors() {
        return 1;
    }

    /** The first scripted echo, from a sensor at the robot's centre looking at it; nothing when there is none. */
    @Override
    public Optional<SonarPing> readSonar(int sensor) {
        if (echoes.isEmpty()) {
            return Optional.empty();
        }
        Point2D e = echoes.get(0);
        return Optional.of(new SonarPing(new Point2D(0, 0), Math.atan2(e.y(), e.x()), Math.hypot(e.x(), e.y()), true));
    }

    @Override
    public void brake(boolean on) {
        integrate();
        brakes.add(on);
        braked = on;
        if (on) {
            left = 0;
            right = 0;
        }
    }

    @Override
    public void acknowledgeFaults() {
        motorFault = false;
    }

    @Override
    public void setBoardDeadman(Duration timeout) {
    }

    @Override
    public void writeLimits(double maxWheelSpeed, double maxWheelAcceleration) {
    }

    @Override
    public PidGains readGains() {
        throw new UnsupportedOperationException();
    }

    @Override
    public PidGains writeGains(PidGains gains) {
        throw new UnsupportedOperationException();
    }

    @Override
    public StepRecording stepTest(int motor, double step) {
        throw new UnsupportedOperationException();
    }

    @Override
    public boolean motorBoardSilentFor(double seconds) {
        return false;
    }

    @Override
    public String faultedBoard() {
        return null;
    }

    @Override
    public double interFrameDelay() {
        return 0.00175;
    }

    @Override
    public double encoderReadWireTime() {
        return 0.0052;
    }

    @Override
    public double wheelWriteWireTime() {
        return 0.0048;
    }

    @Override
    public double optionalReadWireTime() {
        return 0.0052;
    }
}
