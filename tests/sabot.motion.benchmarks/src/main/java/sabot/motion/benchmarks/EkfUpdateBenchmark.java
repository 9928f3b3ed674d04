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

import sabot.localization.EkfNoise;
import sabot.localization.Landmark;
import sabot.localization.MeasurementResult;
import sabot.localization.PoseEkf;
import sabot.model.geometry.Pose2D;

/**
 * Cost of EKF updates (target: &le; 20 &micro;s per update). Each measurement benchmark includes the prediction to
 * the measurement's time, as in use; {@code fullCycle} is one 50 Hz control period's worth: odometry, gyro,
 * accelerometer and magnetometer.
 */
@State(Scope.Thread)
@BenchmarkMode(Mode.AverageTime)
@OutputTimeUnit(TimeUnit.NANOSECONDS)
@Warmup(iterations = 3, time = 1)
@Measurement(iterations = 5, time = 1)
@Fork(1)
public class EkfUpdateBenchmark {

    private PoseEkf ekf;
    private double time;
    private final Landmark landmark = new Landmark("L1", 3, 2);

    @Setup
    public void setUp() {
        ekf = new PoseEkf(Pose2D.ORIGIN, new double[] { 0.01, 0.01, 0.01 }, EkfNoise.defaults(), 0.2);
        ekf.start(0);
    }

    private double next() {
        time += 0.02;
        return time;
    }

    @Benchmark
    public MeasurementResult odometry() {
        return ekf.updateOdometry(next(), 0.02, 0.006, 0.001);
    }

    @Benchmark
    public MeasurementResult gyro() {
        return ekf.updateGyro(next(), 0.05);
    }

    @Benchmark
    public MeasurementResult landmarkRangeBearing() {
        Pose2D p = ekf.pose();
        double dx = landmark.x() - p.x();
        double dy = landmark.y() - p.y();
        return ekf.updateLandmark(next(), landmark, Math.hypot(dx, dy), Math.atan2(dy, dx) - p.theta(), 0.02, 0.01);
    }

    @Benchmark
    public MeasurementResult fullCycle() {
        double t = next();
        ekf.updateOdometry(t, 0.02, 0.006, 0.001);
        ekf.updateGyro(t, 0.05);
        ekf.updateAccelerometer(t, 0.0);
        return ekf.updateHeading(t, ekf.pose().theta());
    }
}
