package sabot.onboard.motion.loop;

import java.util.function.Predicate;

import sabot.model.path.Trajectory;
import sabot.model.path.TrajectorySample;

/** The trajectory ahead of the robot, sampled for the path-ahead checks (the echoes', the other robots'). */
final class PathAhead {

    /** Step along the trajectory ahead at which it is checked, s. */
    static final double STEP = 0.1;

    private PathAhead() {
    }

    /**
     * @param from      trajectory time from which to look, s
     * @param lookahead s of driving checked
     * @return whether {@code blocked} holds at a sample of the trajectory between {@code from} and {@code from +
     *         lookahead} (its end at most)
     */
    static boolean blocked(Trajectory trajectory, double from, double lookahead, Predicate<TrajectorySample> blocked) {
        double end = Math.min(trajectory.duration(), from + lookahead);
        for (double s = from; s <= end; s += STEP) {
            if (blocked.test(trajectory.sample(s))) {
                return true;
            }
        }
        return false;
    }
}
