/**
 * The robot's control loop as plain Java (no OSGi): {@link sabot.onboard.motion.loop.ControlLoop} and what it is made
 * of — its host ({@link sabot.onboard.motion.loop.LoopHost}), clock ({@link sabot.onboard.motion.loop.LoopClock}),
 * boards ({@link sabot.onboard.motion.loop.RobotBoards}), settings snapshot
 * ({@link sabot.onboard.motion.loop.LoopSettings}), estimator ({@link sabot.onboard.motion.loop.Localizer}), planner
 * ({@link sabot.onboard.motion.loop.NavigationPlanner}) and control laws
 * ({@link sabot.onboard.motion.loop.LoopControllers}). The {@code motion} task runs it on the robot; tests and the
 * motion simulation ({@code tools/sabot.motion.sim}) drive the same loop period by period with fake boards and a fake
 * clock.
 */
package sabot.onboard.motion.loop;
