package sabot.onboard.motion.loop;

import java.nio.file.Path;
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

import sabot.model.geometry.Point2D;
import sabot.model.geometry.Pose2D;
import sabot.model.map.MapServerFormat;

/**
 * Cost of one sonar ping on the obstacle layer ({@link EchoMemory#add}): its cone cleared up to the echo and, for an
 * echo the map does not explain, the arc marked; the loop does this once per sonar read (about 9 a second). In this
 * package because the layer is the loop's own. {@code range}: the echo's range, m; {@code silence}: a ping that heard
 * nothing (its cone cleared to 4 m). The robot stands in the lab's lower corridor facing east.
 */
@State(Scope.Thread)
@BenchmarkMode(Mode.AverageTime)
@OutputTimeUnit(TimeUnit.NANOSECONDS)
@Warmup(iterations = 3, time = 1)
@Measurement(iterations = 5, time = 1)
@Fork(1)
public class EchoMemoryBenchmark {

    @Param({ "1", "3", "silence" })
    public String range;

    private EchoMemory memory;
    private SonarPing ping;
    private final Pose2D pose = new Pose2D(1.5, 1.0, 0);
    private double t;

    @Setup
    public void setUp() throws Exception {
        NavigationPlanner planner = new NavigationPlanner(MapServerFormat.load(Path.of(System.getProperty(
                "sabot.map", "onboard-bridge/maps/lab.yaml"))).grid(), LoopDefaults.PLANNER_ALGORITHM, 1,
                LoopDefaults.ROBOT_RADIUS, LoopDefaults.INFLATION_RADIUS);
        memory = new EchoMemory(planner);
        Point2D sensor = new Point2D(0.2, 0);
        ping = range.equals("silence") ? SonarPing.silence(sensor, 0) : new SonarPing(sensor, 0, Double.parseDouble(
                range), true);
    }

    @Benchmark
    public boolean add() {
        t += 0.1;
        return memory.add(t, pose, ping);
    }
}
