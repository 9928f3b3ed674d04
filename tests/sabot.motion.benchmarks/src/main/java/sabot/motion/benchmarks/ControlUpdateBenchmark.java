package sabot.motion.benchmarks;

import java.util.concurrent.TimeUnit;

import org.openjdk.jmh.annotations.Benchmark;
import org.openjdk.jmh.annotations.BenchmarkMode;
import org.openjdk.jmh.annotations.Fork;
import org.openjdk.jmh.annotations.Measurement;
import org.openjdk.jmh.annotations.Mode;
import org.openjdk.jmh.annotations.OutputTimeUnit;
import org.openjdk.jmh.annotations.Scope;
import org.openjdk.jmh.annotations.Setup;
import org.openjdk.jmh.annotations.State;
import org.openjdk.jmh.annotations.Warmup;

import sabot.control.ControlCommand;
import sabot.control.Controllers;
import sabot.control.DflGains;
import sabot.control.MotionLimits;
import sabot.control.PseudoinverseGains;
import sabot.control.TrackingController;
import sabot.control.VelocitySmoother;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.path.Trajectory;
import sabot.model.path.TrajectorySample;
import sabot.model.robot.RobotDescriptions;
import sabot.motion.sim.Scenario;

/**
 * Cost of one control update (target: &le; 2 &micro;s). {@code dfl} and {@code pseudoinverse} time the control law
 * alone on a pre-sampled reference; {@code dflWithReferenceAndSmoother} adds what a control cycle also does:
 * sampling the spline trajectory at t (arc-length inversion) and the velocity smoother.
 */
@State(Scope.Thread)
@BenchmarkMode(Mode.AverageTime)
@OutputTimeUnit(TimeUnit.NANOSECONDS)
@Warmup(iterations = 3, time = 1)
@Measurement(iterations = 5, time = 1)
@Fork(1)
public class ControlUpdateBenchmark {

    private static final int SAMPLES = 2048;

    private TrackingController dfl;
    private TrackingController pseudoinverse;
    private VelocitySmoother smoother;
    private Trajectory trajectory;
    private TrajectorySample[] references;
    private Pose2D[] poses;
    private int i;
    private double time;

    @Setup
    public void setUp() {
        MotionLimits limits = MotionLimits.of(RobotDescriptions.defaults());
        dfl = Controllers.dynamicFeedbackLinearization(DflGains.of(2, 1), limits);
        pseudoinverse = Controllers.pseudoinverse(new PseudoinverseGains(2, 4));
        smoother = new VelocitySmoother(limits, 0.5);
        trajectory = Scenario.LEMNISCATE.trajectory(limits);
        references = new TrajectorySample[SAMPLES];
        poses = new Pose2D[SAMPLES];
        for (int k = 0; k < SAMPLES; k++) {
            TrajectorySample r = trajectory.sample(5 + k * 0.02);
            references[k] = r;
            poses[k] = new Pose2D(r.x() + 0.01 * Math.sin(k), r.y() - 0.01 * Math.cos(k), r.theta() + 0.02 * Math.sin(k));
        }
        dfl.commandApplied(new Twist2D(0.3, 0));
    }

    private double nextTime() {
        time += 0.02;
        return time;
    }

    @Benchmark
    public ControlCommand dfl() {
        int k = i++ & (SAMPLES - 1);
        ControlCommand c = dfl.update(nextTime(), poses[k], references[k]);
        dfl.commandApplied(c.twist());
        return c;
    }

    @Benchmark
    public ControlCommand pseudoinverse() {
        int k = i++ & (SAMPLES - 1);
        return pseudoinverse.update(nextTime(), poses[k], references[k]);
    }

    @Benchmark
    public Twist2D dflWithReferenceAndSmoother() {
        int k = i++ & (SAMPLES - 1);
        double t = nextTime();
        TrajectorySample r = trajectory.sample(5 + (t % 38.0));
        ControlCommand c = dfl.update(t, poses[k], r);
        Twist2D applied = smoother.smooth(t, c.twist());
        dfl.commandApplied(applied);
        return applied;
    }
}
