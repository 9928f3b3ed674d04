package sabot.control.trajectory;

import java.util.List;

import sabot.model.path.Trajectory;
import sabot.model.path.TrajectorySample;

/**
 * Trajectories played one after the other (e.g. the legs and turns of a square with stops). Each part's time starts
 * at zero; the sequence shifts them. The caller is responsible for parts that join (end pose of one = start pose of
 * the next).
 */
public final class TrajectorySequence implements Trajectory {

    private final List<Trajectory> parts;
    private final double[] starts;
    private final double duration;
    private final double length;

    public TrajectorySequence(List<? extends Trajectory> parts) {
        if (parts == null || parts.isEmpty()) {
            throw new IllegalArgumentException("a trajectory sequence needs at least one part");
        }
        this.parts = List.copyOf(parts);
        starts = new double[this.parts.size()];
        double t = 0;
        double l = 0;
        for (int i = 0; i < starts.length; i++) {
            starts[i] = t;
            t += this.parts.get(i).duration();
            l += this.parts.get(i).length();
        }
        duration = t;
        length = l;
    }

    @Override
    public double duration() {
        return duration;
    }

    @Override
    public double length() {
        return length;
    }

    /** @return the parts in order */
    public List<Trajectory> parts() {
        return parts;
    }

    /** @return the start time (s) of part {@code i} within the sequence */
    public double startOf(int i) {
        return starts[i];
    }

    @Override
    public TrajectorySample sample(double time) {
        if (!Double.isFinite(time)) {
            throw new IllegalArgumentException("time must be finite, was " + time);
        }
        int i = starts.length - 1;
        while (i > 0 && time < starts[i]) {
            i--;
        }
        TrajectorySample s = parts.get(i).sample(time - starts[i]);
        return new TrajectorySample(time, s.x(), s.y(), s.theta(), s.linearVelocity(), s.angularVelocity(), s.xDot(),
                s.yDot(), s.xDdot(), s.yDdot());
    }
}
