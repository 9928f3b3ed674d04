package sabot.onboard.motion.loop;

import java.util.ArrayList;
import java.util.List;

import sabot.controlml.payload.TrajectoryPoint;
import sabot.model.path.Trajectory;
import sabot.model.path.TrajectorySample;

/**
 * An imposed trajectory (ControlML {@code cm.trajectory} set): the operator's points, interpolated linearly in time
 * (heading along the shorter arc); velocities in the map frame follow from v and θ.
 */
final class SampledTrajectory implements Trajectory {

    /** Sampling step of cm.trajectory answers, s. */
    static final double REPORT_STEP = 0.1;

    private final List<TrajectoryPoint> points;
    private final double length;

    /** @return {@code t} as reported in cm.trajectory: a point every {@link #REPORT_STEP} s (4096 at most) */
    static List<TrajectoryPoint> points(Trajectory t) {
        List<TrajectoryPoint> points = new ArrayList<>();
        int n = (int) Math.min(4095, Math.ceil(t.duration() / REPORT_STEP));
        double step = n == 0 ? 0 : t.duration() / n;
        for (int i = 0; i <= n; i++) {
            TrajectorySample s = t.sample(i * step);
            points.add(new TrajectoryPoint(i * step, s.x(), s.y(), s.theta(), s.linearVelocity(),
                    s.angularVelocity()));
        }
        return points;
    }

    SampledTrajectory(List<TrajectoryPoint> points) {
        this.points = List.copyOf(points);
        double l = 0;
        for (int i = 1; i < points.size(); i++) {
            l += Math.hypot(points.get(i).x() - points.get(i - 1).x(), points.get(i).y() - points.get(i - 1).y());
        }
        this.length = l;
    }

    @Override
    public double duration() {
        return points.get(points.size() - 1).t() - points.get(0).t();
    }

    @Override
    public double length() {
        return length;
    }

    @Override
    public TrajectorySample sample(double time) {
        double t = points.get(0).t() + Math.max(0, Math.min(time, duration()));
        int i = 1;
        while (i < points.size() - 1 && points.get(i).t() < t) {
            i++;
        }
        TrajectoryPoint a = points.get(i - 1);
        TrajectoryPoint b = points.get(i);
        double span = b.t() - a.t();
        double u = span > 0 ? (t - a.t()) / span : 1;
        double theta = a.theta() + u * sabot.model.geometry.Pose2D.normalizeAngle(b.theta() - a.theta());
        double v = a.v() + u * (b.v() - a.v());
        double w = a.omega() + u * (b.omega() - a.omega());
        double acc = span > 0 ? (b.v() - a.v()) / span : 0;
        double c = Math.cos(theta);
        double s = Math.sin(theta);
        return new TrajectorySample(time, a.x() + u * (b.x() - a.x()), a.y() + u * (b.y() - a.y()), theta, v, w,
                v * c, v * s, acc * c - v * w * s, acc * s + v * w * c);
    }
}
