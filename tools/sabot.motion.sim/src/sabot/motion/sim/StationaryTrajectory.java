package sabot.motion.sim;

import sabot.model.geometry.Pose2D;
import sabot.model.path.Trajectory;
import sabot.model.path.TrajectorySample;

/** A goal pose held for a given time: the reference of point stabilization. */
final class StationaryTrajectory implements Trajectory {

    private final Pose2D goal;
    private final double duration;

    StationaryTrajectory(Pose2D goal, double duration) {
        this.goal = goal;
        this.duration = duration;
    }

    @Override
    public double duration() {
        return duration;
    }

    @Override
    public TrajectorySample sample(double time) {
        return TrajectorySample.stationary(time, goal);
    }

    @Override
    public double length() {
        return 0;
    }
}
