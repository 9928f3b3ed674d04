/**
 * The robot's motion as a service: what the ControlML endpoint, the joystick and other tasks command and read.
 * Provided by the onboard control loop ({@code sabot.task.navigation}), used by {@code sabot.task.controlml}.
 * Units: SI and radians, map frame (ROS map_server convention), times from the robot's clock.
 */
package sabot.onboard.robot;
