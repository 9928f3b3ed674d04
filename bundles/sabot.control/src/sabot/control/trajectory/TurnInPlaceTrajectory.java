package sabot.control.trajectory;

import sabot.model.geometry.Pose2D;
import sabot.model.path.Trajectory;
import sabot.model.path.TrajectorySample;

/** A rotation on the spot with a trapezoidal yaw-rate profile: v = 0 throughout, the position fixed. */
public final class TurnInPlaceTrajectory implements Trajectory {

    private final Pose2D start;
    private final double sign;
    private final TrapezoidalTimeLaw law;

    /**
     * @param start        pose where the turn starts
     * @param angle        signed rotation, radians (positive counter-clockwise)
     * @param maxRate      yaw-rate bound, rad/s
     * @param maxAngularAcceleration yaw-acceleration bound, rad/s&sup2;
     */
    public TurnInPlaceTrajectory(Pose2D start, double angle, double maxRate, double maxAngularAcceleration) {
        if (start == null || !start.isFinite() || !Double.isFinite(angle)) {
            throw new IllegalArgumentException("turn needs a finite start pose and angle");
        }
        this.start = start;
        this.sign = Math.signum(angle);
        this.law = new TrapezoidalTimeLaw(Math.abs(angle), maxRate, maxAngularAcceleration);
    }

    @Override
    public double duration() {
        return law.duration();
    }

    @Override
    public double length() {
        return 0;
    }

    @Override
    public TrajectorySample sample(double time) {
        if (!Double.isFinite(time)) {
            throw new IllegalArgumentException("time must be finite, was " + time);
        }
        double[] sl = new double[3];
        law.evaluate(time, sl);
        return new TrajectorySample(time, start.x(), start.y(), start.theta() + sign * sl[0], 0, sign * sl[1], 0, 0, 0, 0);
    }
}
