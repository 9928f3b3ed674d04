package sabot.modbus;

import java.util.OptionalDouble;

/**
 * The latest reading of one sonar sensor.
 *
 * @param sensor   sensor number (0 left, 1 centre, 2 right)
 * @param sequence ping counter, 0–65535, wraps: a new value means a new ping
 * @param angle    beam axis in the robot frame at the ping, rad
 * @param range    range to the echo, m; empty when there was no echo within the maximum range
 * @param x        obstacle x relative to the robot centre, m (forward)
 * @param y        obstacle y relative to the robot centre, m (left)
 * @param valid    the echo is valid (x, y mean something)
 */
public record SonarReading(int sensor, int sequence, double angle, OptionalDouble range, double x, double y,
        boolean valid) {
}
