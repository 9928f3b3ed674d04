package sabot.motion.benchmarks;

import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Random;
import java.util.concurrent.TimeUnit;

import org.openjdk.jmh.annotations.Benchmark;
import org.openjdk.jmh.annotations.BenchmarkMode;
import org.openjdk.jmh.annotations.Fork;
import org.openjdk.jmh.annotations.Measurement;
import org.openjdk.jmh.annotations.Mode;
import org.openjdk.jmh.annotations.OutputTimeUnit;
import org.openjdk.jmh.annotations.Param;
import org.openjdk.jmh.annotations.Scope;
import org.openjdk.jmh.annotations.Setup;
import org.openjdk.jmh.annotations.State;
import org.openjdk.jmh.annotations.Warmup;

import sabot.control.CollisionGuard;
import sabot.control.MotionLimits;
import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.map.MapServerFormat;
import sabot.model.robot.RobotDescriptions;
import sabot.onboard.motion.loop.LoopDefaults;
import sabot.onboard.motion.loop.NavigationPlanner;

/**
 * Cost of the collision guard in one control period: one command at the top speed checked along its arc against the
 * lab map's occupied cells and the sonar echoes in memory, as the loop's guard does. {@code open}: the lower corridor,
 * nothing within the stopping distance, so the whole lookahead is walked (the most work); {@code wall}: 0.3 m before
 * the partition, the arc ends at the first steps. {@code echoes}: cells the sonar marked around the robot (600: the arcs of about
 * 30 echoes, what the obstacle layer holds after 3 s of pings in a cluttered place).
 */
@State(Scope.Thread)
@BenchmarkMode(Mode.AverageTime)
@OutputTimeUnit(TimeUnit.NANOSECONDS)
@Warmup(iterations = 3, time = 1)
@Measurement(iterations = 5, time = 1)
@Fork(1)
public class GuardBenchmark {

    @Param({ "open", "wall" })
    public String place;

    @Param({ "0", "600" })
    public int echoes;

    private CollisionGuard guard;
    private CollisionGuard.ObstacleField field;
    private Pose2D pose;
    private final Twist2D command = new Twist2D(0.5, 0.2);

    @Setup
    public void setUp() throws Exception {
        NavigationPlanner planner = new NavigationPlanner(MapServerFormat.load(Path.of(System.getProperty(
                "sabot.map", "onboard-bridge/maps/lab.yaml"))).grid(), LoopDefaults.PLANNER_ALGORITHM, 1,
                LoopDefaults.ROBOT_RADIUS, LoopDefaults.INFLATION_RADIUS);
        MotionLimits limits = MotionLimits.of(RobotDescriptions.defaults());
        guard = new CollisionGuard(new CollisionGuard.Settings(LoopDefaults.ROBOT_RADIUS, LoopDefaults.GUARD_MARGIN,
                LoopDefaults.GUARD_REACTION_TIME, limits.maxLinearAcceleration(), limits.maxLinearSpeed(),
                LoopDefaults.REVERSE_SPEED));
        pose = place.equals("open") ? new Pose2D(1.5, 1.0, 0) : new Pose2D(2.45, 4.0, 0);
        Random random = new Random(1);
        List<Point2D> points = new ArrayList<>();
        for (int i = 0; i < echoes; i++) {
            // beside and behind the robot, 1 to 3 m away: remembered, but not on its arc
            double bearing = Math.PI / 2 + random.nextDouble() * Math.PI;
            double range = 1 + 2 * random.nextDouble();
            points.add(new Point2D(pose.x() + range * Math.cos(bearing), pose.y() + range * Math.sin(bearing)));
        }
        field = (x, y, limit) -> {
            double best = limit;
            for (Point2D p : points) {
                best = Math.min(best, Math.hypot(p.x() - x, p.y() - y));
            }
            return planner.clearance(x, y, best);
        };
    }

    @Benchmark
    public CollisionGuard.Decision limit() {
        return guard.limit(pose, command, field);
    }
}
