package sabot.modbus;

/**
 * One wheel's state as the SACT board measured it.
 *
 * @param position        measured encoder position, counts; wraps modulo 2³² (use differences, e.g.
 *                        {@code b.position() - a.position()} in int arithmetic)
 * @param speed           measured wheel speed over the last 16 control periods, rad/s (positive drives forward)
 * @param current         motor current, A (mean of the last 16 samples)
 * @param faultLatched    a fault is latched: the motor brakes until {@link SactClient#acknowledgeFaults()}
 * @param overCurrent     the current limit was exceeded
 * @param followingError  |commanded − measured| exceeded the following-error limit
 * @param braking         the H-bridge shorts the motor
 * @param atSetpoint      the ramped velocity has reached the set-point
 */
public record WheelState(int position, double speed, double current, boolean faultLatched, boolean overCurrent,
        boolean followingError, boolean braking, boolean atSetpoint) {
}
