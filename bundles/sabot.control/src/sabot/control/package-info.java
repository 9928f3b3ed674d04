/**
 * Motion control of a differential-drive robot, free of OSGi, XMPP and UI: the unicycle model and its RK4
 * integration ({@link sabot.control.UnicycleModel}), the wheel-speed map ({@link sabot.control.DifferentialDrive}),
 * motion limits derived from the robot description ({@link sabot.control.MotionLimits}), tracking controllers behind
 * one SPI ({@link sabot.control.TrackingController}, built by {@link sabot.control.Controllers}), and the Nav2-style
 * helpers a navigation stack expects: {@link sabot.control.GoalChecker}, {@link sabot.control.ProgressChecker} and
 * {@link sabot.control.VelocitySmoother}.
 * <p>
 * SI units and radians; times in seconds on a monotonic clock chosen by the caller.
 */
package sabot.control;
