package sabot.onboard.robot;

import java.time.Duration;
import java.time.Instant;
import java.util.List;
import java.util.Optional;

import org.osgi.annotation.versioning.ProviderType;

import sabot.controlml.payload.Goal;
import sabot.controlml.payload.GridMap;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.MissionTarget;
import sabot.controlml.payload.LimitsPayload;
import sabot.controlml.payload.Obstacles;
import sabot.controlml.payload.PidGains;
import sabot.controlml.payload.PoseEstimate;
import sabot.controlml.payload.TrajectoryPayload;
import sabot.controlml.payload.VelocityCommand;
import sabot.model.geometry.Pose2D;
import sabot.model.robot.BatteryState;
import sabot.model.robot.PassageClaim;
import sabot.pidstep.controlml.StepTest;
import sabot.model.geometry.Twist2D;

/**
 * The robot's motion: one fixed-rate control loop (read encoders and inertial sample, update the estimate, run the
 * tracker, write wheel speeds) behind a thread-safe facade. A command returns once the loop has taken it (within a
 * period), so that the next read shows its effect; {@link #navigateTo} plans on the caller's thread first (under a
 * millisecond on a lab-sized map) so that an unreachable goal is refused with its reason. A refused command throws
 * {@link CommandRefused} and changes nothing. Reads never block on the bus or the network: they return the loop's
 * last published state; only {@link #gains} and {@link #setGains} talk to the motor board (a few transactions).
 */
@ProviderType
public interface RobotMotion {

    /** @return the latest pose estimate (map frame, metres/radians) with its covariance and time; never null */
    PoseEstimate pose();

    /** @return the twist being executed (from the wheels' measured speeds) with its time; never null */
    VelocityCommand velocity();

    /**
     * Re-localises: the estimate is reset to {@code pose} (covariance back to its initial value). Refused while moving.
     */
    void relocalise(Pose2D pose) throws CommandRefused;

    /**
     * A joystick twist (m/s, rad/s). Clamped to the limits; the robot stops by itself when no twist arrives for the
     * teleop timeout (deadman, default 0.5 s). Refused (INVALID_STATE) while a mission runs, or after a fault until
     * the fault is cleared by a new command. Dropped (STALE_COMMAND) when sent longer ago than the teleop task's
     * {@code maxAge}.
     *
     * @param sent when the operator's client sent the twist (its ControlML {@code time}), for the command-to-wheel
     *             latency figure; may be null
     * @param age  how long ago it was sent, on this robot's clock (ControlML's {@code Request.age})
     */
    void teleop(Twist2D twist, Instant sent, Duration age) throws CommandRefused;

    /** @return the goal of the current or last mission, if any */
    Optional<Goal> goal();

    /**
     * Starts a mission to {@code goal}: plan on the map, follow, stop within the goal's tolerances. Replaces a
     * running mission. Refused when the goal is off the map or in an obstacle (INVALID_VALUE), no path exists
     * (INVALID_VALUE, "unreachable"), in maintenance (MAINTENANCE_LOCK) or in a board fault (DEVICE_FAULT).
     */
    void navigateTo(Goal goal) throws CommandRefused;

    /**
     * Starts or queues a mission of several targets ({@code cm.mission} with targets): the robot drives to each in
     * order and does its action there (pass through, stop, wait, dock). Every leg is planned before the mission is
     * taken (the first from where the robot stands, each next from the target before), so that an unreachable target
     * is refused with its number and reason; each leg is planned again from where the robot stands when it starts.
     *
     * @param targets the targets in order, 1..{@link MissionStatus#MAX_TARGETS}; their states are not read
     * @param queue   false: start now, replacing a running mission (the queue stays); true: run after the running
     *                mission and those queued before (at once when none runs)
     * @throws CommandRefused INVALID_VALUE for a target off the map, in an obstacle or unreachable; MAINTENANCE_LOCK in
     *                        maintenance; DEVICE_FAULT with a board fault; BUSY when the queue is full; nothing changed
     */
    void startMission(List<MissionTarget> targets, boolean queue) throws CommandRefused;

    /** @return the trajectory being followed (empty point list when none); never null */
    TrajectoryPayload trajectory();

    /** Follows an imposed trajectory instead of a planned one (a mission without a goal pose check). */
    void follow(TrajectoryPayload trajectory) throws CommandRefused;

    /** @return the obstacles the sonar board sees now, map frame; never null */
    Obstacles obstacles();

    /** @return the static map the planner uses; never null */
    GridMap map();

    /** Replaces the static map (refused while a mission runs). */
    void replaceMap(GridMap map) throws CommandRefused;

    /** @return the motion limits in force; never null */
    LimitsPayload limits();

    /** Sets new limits, never above the robot's physical ones (INVALID_VALUE). Applies at the next control period. */
    void setLimits(LimitsPayload limits) throws CommandRefused;

    /**
     * @return the battery as the power board last measured it (about once a second; {@link BatteryState#measured()}
     *         says when)
     * @throws CommandRefused DEVICE_FAULT when the power board's last read failed (the message says why: silent, or a
     *                        reading no battery gives) or it has not been read yet
     */
    BatteryState battery() throws CommandRefused;

    /**
     * @return whether the robot stands on its dock charging after a low battery, until it is charged again (presence
     *         Away "charging"); listeners hear of a change as a {@link MotionListener#missionChanged} with the mission
     *         as it is
     */
    default boolean charging() {
        return false;
    }

    /**
     * @return the robot's claim on a narrow passage of its map (docs/PASSAGES.md) as of the last control period, empty
     *         for none ({@code cm.passage})
     * @since 0.3
     */
    default Optional<PassageClaim> passage() {
        return Optional.empty();
    }

    /** @return the motor gains read back from the motor board; DEVICE_FAULT when the board does not answer */
    PidGains gains() throws CommandRefused;

    /** Writes the motor gains and reads them back; bad gains are refused with nothing written. */
    PidGains setGains(PidGains gains) throws CommandRefused;

    /**
     * The PID step test ({@code cm.pid.step}): in maintenance mode only, releases the brakes, steps one motor's
     * position loop by {@code step} metres of wheel travel with the gains on the motor board, lets the board record
     * the response at its control rate, and brakes again (also when the test fails). Bounded: the step is limited by
     * the board (and kept under its following-error limit), the wait by the recording's length.
     *
     * @param motor the motor, numbered as in {@code cm.pid}
     * @param step  m of wheel travel, non-zero
     * @return the request with the samples (t s, set-point m, measured m)
     * @throws CommandRefused INVALID_STATE when not in maintenance; INVALID_VALUE for an unknown motor or a step over
     *                        the limit (nothing moved); DEVICE_FAULT when the board refuses or does not answer;
     *                        UNSUPPORTED_OPERATION on a robot without a step test (this default)
     */
    default StepTest stepTest(int motor, double step) throws CommandRefused {
        throw new CommandRefused(sabot.controlml.ControlMlCondition.UNSUPPORTED_OPERATION,
                "this robot has no PID step test");
    }

    /** @return the mission's state, progress and detail (the reason of a failure or fault); never null */
    MissionStatus mission();

    /**
     * Applies a {@code cm.mission} set: PAUSED pauses a running mission, RUNNING resumes a paused one, ABORTED aborts;
     * {@code maintenance} switches maintenance mode (the state is then ignored; entering maintenance aborts a running or
     * paused mission, and the robot takes no motion command until maintenance is switched off).
     */
    void command(MissionStatus command) throws CommandRefused;

    /** Brakes now and ends any mission or teleop with {@code reason} (failed for a fault, aborted otherwise). */
    void stop(String reason, boolean fault);

    /** Adds a listener of mission state changes (called off the control loop's thread). */
    void addListener(MotionListener listener);

    /** Removes a listener added with {@link #addListener}. */
    void removeListener(MotionListener listener);
}
