package sabot.modbus;

import java.io.IOException;
import java.time.Duration;

import org.osgi.annotation.versioning.ProviderType;

/**
 * The SACT motor board (slave 1): two wheel motors. Wheel speeds are in rad/s at the wheel (positive drives the robot
 * forward); conversions use the board's own configuration (encoder lines, gear ratio) read when the bus opened.
 * Every method is one Modbus transaction unless it says otherwise, and throws {@link BoardException} when the board
 * does not answer well, {@link IllegalArgumentException} (nothing sent) for a value outside the map's static bounds.
 */
@ProviderType
public interface SactClient extends Board {

    /**
     * @return the configuration read when the bus opened (or now, if that failed)
     * @throws IOException the board does not answer
     */
    SactConfig config() throws IOException;

    /**
     * Sets both wheels' velocity set-points in one write (file 4 records 0–1), so both change in the same control
     * step. A speed above the board's {@code max_speed} is refused by the board: {@link BoardException} of kind
     * {@link BoardException.Kind#EXCEPTION} with code 3.
     *
     * @param leftRadPerS  left wheel, rad/s
     * @param rightRadPerS right wheel, rad/s
     */
    void setWheelSpeeds(double leftRadPerS, double rightRadPerS) throws IOException;

    /** @return wheel positions, speeds, currents and status flags of both motors, in one 0x14 transaction */
    Wheels readWheels() throws IOException;

    /**
     * Reads both encoder positions only: one 0x14 transaction with two two-register sub-requests, the shortest read
     * a control loop can do each period (see {@link #readPositionsWireTime}).
     *
     * @return both wheels' encoder counts (wrap modulo 2^32)
     */
    WheelCounts readPositions() throws IOException;

    /** @return the computed wire time of {@link #readPositions} at the bus's baud rate */
    Duration readPositionsWireTime();

    /**
     * @param on true: zero both set-points and short both motors (one write); false: release both brakes
     */
    void brake(boolean on) throws IOException;

    /** @return one motor's PID gains */
    SactGains readGains(Motor motor) throws IOException;

    /**
     * Writes one motor's PID gains. Every gain is checked against the register map's bounds first; if one is out of
     * bounds nothing is written.
     *
     * @throws IllegalArgumentException a gain outside its bounds, naming it
     */
    void writeGains(Motor motor, SactGains gains) throws IOException;

    /**
     * Writes the board's wheel surface limits (file 3 records 4–5); a limit that tightens also clamps what is
     * commanded. The cached {@link #config()} is read again.
     *
     * @param maxSpeed m/s
     * @param maxAccel m/s²
     */
    void writeLimits(double maxSpeed, double maxAccel) throws IOException;

    /**
     * Sets the board's own deadman: with no velocity write for this long both set-points go to zero.
     *
     * @param timeout whole milliseconds, {@link Duration#ZERO} turns it off
     */
    void setCommandTimeout(Duration timeout) throws IOException;

    /** Clears both motors' latched faults (writes 0 to both status records, one write). */
    void acknowledgeFaults() throws IOException;

    /**
     * Adds {@code counts} to one motor's commanded position (step-response tuning), once: the write carries an
     * idempotency key, so a retry after a lost answer is not applied again (also for {@link #startStepCapture}).
     *
     * @param counts encoder counts, within the map's bounds (±2048)
     */
    void positionStep(Motor motor, int counts) throws IOException;

    /**
     * Steps one motor's commanded position by {@code counts} and starts the board's recording of the response (file
     * {@code step_capture}, two transactions: which motor and how often, then the step). The board refuses the step
     * (exception 4, {@link BoardException}) while that motor is braked or its fault is latched.
     *
     * @param decimation control periods between two samples, within the map's bounds
     * @throws IllegalArgumentException counts or decimation outside the map's bounds (nothing sent)
     */
    void startStepCapture(Motor motor, int counts, int decimation) throws IOException;

    /**
     * @return the recording started by the last {@link #startStepCapture}, as far as it has got (one transaction for
     *         its progress, then enough to read the samples: each answer must fit one PDU)
     */
    StepCapture readStepCapture() throws IOException;

    /** @return the wire time of {@link #readWheels()} */
    Duration readWheelsWireTime();

    /** @return the wire time of {@link #setWheelSpeeds(double, double)} */
    Duration setWheelSpeedsWireTime();
}
