package sabot.onboard.motion.loop;

import java.io.IOException;
import java.time.Duration;
import java.time.Instant;
import java.util.Optional;

import sabot.controlml.payload.PidGains;
import sabot.model.robot.BatteryState;
import sabot.modbus.LandmarkSighting;
import sabot.modbus.WheelCounts;

/**
 * What the control loop needs of the robot's RS-485 bus, in SI units: one method per bus transaction, so the loop can
 * budget its period. Provided as a service by the {@code bus} task over {@code sabot.modbus}. The
 * bus serialises transactions itself, callers other than the loop (gains) take a few milliseconds of bus time.
 */
public interface RobotBoards {

    /** The inertial sample the estimator uses: yaw rate (rad/s) and longitudinal specific force (m/s²). */
    record ImuSample(double yawRate, double forwardAcceleration) {
    }

    /** The motor board refuses to drive: a motor fault is latched (the board brakes that motor by itself). */
    final class MotorFaultException extends IOException {
        private static final long serialVersionUID = 1L;

        /** @param what which motor and why, for a person (e.g. "left motor: following error") */
        public MotorFaultException(String what, Throwable cause) {
            super(what, cause);
        }
    }

    /** @return both encoders, one transaction */
    WheelCounts readEncoders() throws IOException;

    /**
     * Writes both wheel speed set-points (rad/s at the wheel, positive forward) in one transaction.
     *
     * @throws MotorFaultException the board refused because a motor fault is latched (one more transaction read why)
     */
    void writeWheelSpeeds(double left, double right) throws IOException;

    /** @return the inertial board's latest sample, one transaction */
    ImuSample readImu() throws IOException;

    /** @return the landmark board's latest measurement, one transaction */
    LandmarkSighting readLandmark() throws IOException;

    /** @return whether the landmark board (optional: not every robot has one) has stopped answering */
    boolean landmarkBoardFaulted();

    /**
     * @param now the loop's wall time, the reading's stamp
     * @return the power board's latest measurement of the battery with its design capacity, one transaction (two the
     *         first time: the capacity is read once)
     * @throws IOException the board did not answer, or answered a reading no battery gives (named in the message)
     */
    BatteryState readBattery(Instant now) throws IOException;

    /** @return whether the power board (optional: a robot on a bench supply has none) has stopped answering */
    boolean powerBoardFaulted();

    /** @return the number of sonar sensors */
    int sonarSensors();

    /**
     * @return the latest ping of one sonar sensor (where it sat and pointed, what answered), or empty when the board
     *         cannot say where the sensor is; one transaction
     */
    Optional<SonarPing> readSonar(int sensor) throws IOException;

    /** Brakes both motors (set-points zeroed) or releases the brake. */
    void brake(boolean on) throws IOException;

    /** Clears latched motor faults. */
    void acknowledgeFaults() throws IOException;

    /** Sets the motor board's own deadman: no set-point write for this long and it stops the wheels. */
    void setBoardDeadman(Duration timeout) throws IOException;

    /** Sets the motor board's wheel speed and acceleration limits (m/s, m/s² at the wheel rim). */
    void writeLimits(double maxWheelSpeed, double maxWheelAcceleration) throws IOException;

    /** @return the gains read back from the board */
    PidGains readGains() throws IOException;

    /** Writes the gains (validated before anything is written) and returns them read back. */
    PidGains writeGains(PidGains gains) throws IOException;

    /**
     * A position step of one motor recorded by the motor board.
     *
     * @param step         the step applied, m of wheel travel (the requested one rounded to whole counts)
     * @param samplePeriod s between two samples
     * @param measured     m of wheel travel from the position at the step, one per sample
     */
    record StepRecording(double step, double samplePeriod, double[] measured) {
    }

    /**
     * Releases the brakes, steps one motor's position loop by {@code step} metres, waits for the board's recording,
     * reads it, and brakes again whatever happened.
     *
     * @throws IllegalArgumentException an unknown motor, or a step the board cannot take (over its bound, or one that
     *                                  would trip its following-error limit): nothing moved
     */
    StepRecording stepTest(int motor, double step) throws IOException;

    /** @return whether the motor board's last good answer is older than {@code seconds} (or it never answered) */
    boolean motorBoardSilentFor(double seconds);

    /** @return the name of the first board that has not answered for longer than the bus's fault time, or null */
    String faultedBoard();

    /** @return the silence the bus keeps between an answer and the next request (t3.5), seconds */
    double interFrameDelay();

    /** @return computed wire time of {@link #readEncoders}, seconds */
    double encoderReadWireTime();

    /** @return computed wire time of {@link #writeWheelSpeeds}, seconds */
    double wheelWriteWireTime();

    /** @return computed wire time of the longest of the loop's optional reads (IMU, one sonar sensor, landmark, power), s */
    double optionalReadWireTime();
}
