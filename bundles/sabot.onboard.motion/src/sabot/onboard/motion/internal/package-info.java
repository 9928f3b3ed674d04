/**
 * The robot's motion tasks: the Modbus bus ({@code bus}), the pose estimate ({@code localizer}), the path planner
 * ({@code planner}), the trajectory tracker ({@code tracker}), the joystick ({@code teleop}) and the fixed-rate control
 * loop that ties them together and provides {@link sabot.onboard.robot.RobotMotion} ({@code motion}).
 */
package sabot.onboard.motion.internal;
