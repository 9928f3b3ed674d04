package sabot.onboard.motion.loop;

/**
 * Everything the control loop is configured with, as one immutable snapshot: the motion task builds it from the
 * motion, localizer, planner, tracker and teleop tasks' settings each time one of them changes and hands it to the
 * loop ({@link ControlLoop#settingsChanged}); the loop never reads a task's configuration itself.
 *
 * @param rate                 periods per second, Hz
 * @param statusPeriod         s between two status log lines (0: none)
 * @param obstacleMemory       s a sonar echo stays in the obstacle list
 * @param blockedLookahead     s of driving along the trajectory ahead checked against echoes
 * @param blockedClearance     m beyond the robot radius an echo must keep from the path ahead
 * @param goalTolerance        m, position tolerance at a goal that does not carry its own (imposed trajectories)
 * @param joystick             whether joystick twists are accepted (the teleop task runs)
 * @param deadman              s without a joystick twist after which the robot brakes, judged on the twist's receive
 *                             time ({@code teleop.timeout}); the one deadman of the loop (see {@link ControlLoop})
 * @param robotRadius          m, the robot's footprint (planner)
 * @param blockedTimeout       s the robot waits for a way around a blocked path before the mission fails
 * @param speedHeadroom        fraction of the top speeds a trajectory is planned with
 * @param accelerationHeadroom fraction of the accelerations a trajectory is planned with
 * @param progressRadius       m the robot must move within {@code progressTime}, or the mission replans
 * @param progressTime         s allowed to move {@code progressRadius}
 * @param settleTimeout        s allowed to settle on the goal after the trajectory ends
 * @param localizer            the pose estimate's settings
 * @param guard                the collision guard's settings
 */
public record LoopSettings(double rate, double statusPeriod, double obstacleMemory, double blockedLookahead,
        double blockedClearance, double goalTolerance, boolean joystick, double deadman, double robotRadius,
        double blockedTimeout, double speedHeadroom, double accelerationHeadroom, double progressRadius,
        double progressTime, double settleTimeout, LocalizerSettings localizer, GuardSettings guard) {

    public LoopSettings {
        if (!(rate > 0) || !(deadman > 0)) {
            throw new IllegalArgumentException("rate and deadman must be > 0, were " + rate + " Hz, " + deadman + " s");
        }
    }

    /** @return the period, ns */
    public long periodNanos() {
        return Math.round(1e9 / rate);
    }

    /** @return the same settings with status log lines every {@code period} s (0: none) */
    public LoopSettings withStatusPeriod(double period) {
        return new LoopSettings(rate, period, obstacleMemory, blockedLookahead, blockedClearance, goalTolerance,
                joystick, deadman, robotRadius, blockedTimeout, speedHeadroom, accelerationHeadroom, progressRadius,
                progressTime, settleTimeout, localizer, guard);
    }

    /** @return the same settings with the joystick accepted (or not) and its deadman */
    public LoopSettings withJoystick(boolean accepted, double timeout) {
        return new LoopSettings(rate, statusPeriod, obstacleMemory, blockedLookahead, blockedClearance, goalTolerance,
                accepted, timeout, robotRadius, blockedTimeout, speedHeadroom, accelerationHeadroom, progressRadius,
                progressTime, settleTimeout, localizer, guard);
    }
}
