/**
 * The robot description: the one configuration that holds the drive's physical constants (wheel radius, track,
 * gear ratio, encoder resolution, motor no-load speed) and motion limits (speed, acceleration, lateral
 * acceleration). Every algorithm that needs one of these numbers receives a {@link sabot.model.robot.RobotDescription};
 * no bundle repeats them as literals. SI units and radians throughout. {@link sabot.model.robot.BatteryState} is the
 * battery as the power board measured it;
 * {@link sabot.model.robot.PeerRobot} another robot of the fleet as this one last heard of it.
 */
package sabot.model.robot;
