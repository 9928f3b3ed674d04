package sabot.motion.sim;

import java.io.IOException;
import java.time.Duration;
import java.time.Instant;
import java.util.Optional;

import sabot.control.WheelSpeeds;
import sabot.controlml.payload.PidGains;
import sabot.model.robot.BatteryState;
import sabot.modbus.LandmarkSighting;
import sabot.modbus.WheelCounts;
import sabot.onboard.motion.loop.RobotBoards;
import sabot.onboard.motion.loop.SonarPing;

/**
 * The robot's boards over a {@link SimulatedRobot} and a {@link SimulatedImu}: the encoder read answers the true
 * wheels' counts, the wheel write sets the speeds the wheels turn at until the next write ({@link #drive} moves the
 * truth by one period), the inertial read samples the gyro and accelerometer on the true motion of the last period.
 * There is no landmark board and no sonar; the bus never faults and its transactions take no simulated time (so their
 * wire times are zero, and every spare slot has the time for its read).
 */
final class SimulatedBoards implements RobotBoards {

    private final SimulatedRobot truth;
    private final SimulatedImu imu;
    private WheelSpeeds setPoints = WheelSpeeds.ZERO;
    private boolean braked;

    SimulatedBoards(SimulatedRobot truth, SimulatedImu imu) {
        this.truth = truth;
        this.imu = imu;
    }

    /** Moves the truth for {@code dt} s at the set-points last written (none while braked). */
    void drive(double dt) {
        truth.step(braked ? WheelSpeeds.ZERO : setPoints, dt);
        imu.advance(dt);
    }

    /** @return the robot the boards belong to */
    SimulatedRobot truth() {
        return truth;
    }

    /** @return the wheel set-points in force, rad/s */
    WheelSpeeds setPoints() {
        return braked ? WheelSpeeds.ZERO : setPoints;
    }

    @Override
    public WheelCounts readEncoders() {
        return new WheelCounts(truth.leftCount(), truth.rightCount());
    }

    @Override
    public void writeWheelSpeeds(double left, double right) {
        setPoints = new WheelSpeeds(left, right);
    }

    @Override
    public ImuSample readImu() {
        return new ImuSample(imu.gyro(truth.lastTwist().angular()), imu.accelerometer(truth.lastAcceleration()));
    }

    @Override
    public LandmarkSighting readLandmark() throws IOException {
        throw new IOException("no landmark board");
    }

    @Override
    public boolean landmarkBoardFaulted() {
        return true;
    }

    @Override
    public BatteryState readBattery(Instant now) throws IOException {
        throw new IOException("no power board");
    }

    @Override
    public boolean powerBoardFaulted() {
        return true;
    }

    @Override
    public int sonarSensors() {
        return 0;
    }

    @Override
    public Optional<SonarPing> readSonar(int sensor) {
        return Optional.empty();
    }

    @Override
    public void brake(boolean on) {
        braked = on;
        if (on) {
            setPoints = WheelSpeeds.ZERO;
        }
    }

    @Override
    public void acknowledgeFaults() {
        // no motor fault is simulated
    }

    @Override
    public void setBoardDeadman(Duration timeout) {
        // the loop writes every period: the board's deadman never fires in the simulation
    }

    @Override
    public void writeLimits(double maxWheelSpeed, double maxWheelAcceleration) {
        // the wheels follow the set-points exactly; the loop's own limits are checked on what it writes
    }

    @Override
    public PidGains readGains() {
        throw new UnsupportedOperationException("the simulated motor board has no speed loop to tune");
    }

    @Override
    public PidGains writeGains(PidGains gains) {
        throw new UnsupportedOperationException("the simulated motor board has no speed loop to tune");
    }

    @Override
    public StepRecording stepTest(int motor, double step) {
        throw new UnsupportedOperationException("the simulated motor board has no position loop");
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
        return 0;
    }

    @Override
    public double encoderReadWireTime() {
        return 0;
    }

    @Override
    public double wheelWriteWireTime() {
        return 0;
    }

    @Override
    public double optionalReadWireTime() {
        return 0;
    }
}
