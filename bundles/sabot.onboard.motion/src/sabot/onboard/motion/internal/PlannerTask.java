package sabot.onboard.motion.internal;

import java.io.IOException;
import java.nio.file.Path;
import java.util.List;

import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;
import org.osgi.service.component.annotations.Deactivate;
import org.osgi.service.metatype.annotations.AttributeDefinition;
import org.osgi.service.metatype.annotations.Designate;
import org.osgi.service.metatype.annotations.ObjectClassDefinition;
import org.osgi.service.metatype.annotations.Option;

import sabot.model.geometry.Point2D;
import sabot.model.map.MapLandmark;
import sabot.model.map.MapServerFormat;
import sabot.model.map.Passage;
import sabot.onboard.motion.loop.LoopDefaults;
import sabot.onboard.motion.loop.NavigationPlanner;
import sabot.onboard.task.OnboardTask;

/**
 * Task {@code planner}: the map (ROS map_server YAML + image) and the path planner (LPN by default; any name of
 * {@code sabot.planner.Planners}). Swapping the algorithm is a configuration change. Settings:
 * {@link Config}.
 */
@Designate(ocd = PlannerTask.Config.class, factory = false)
@Component(name = "sabot.task.planner", configurationPolicy = ConfigurationPolicy.REQUIRE,
        service = { OnboardTask.class, PlannerTask.class })
public final class PlannerTask implements OnboardTask {

    /** The task's settings: its Metatype description, generated from these annotations. */
    @ObjectClassDefinition(id = "sabot.task.planner", name = "Planner task",
            description = "Map and path planner (LPN navigation function by default).")
    public @interface Config {
        @AttributeDefinition(name = "Map", description = "The map: a ROS map_server YAML file.")
        String map();

        /** The names are {@code Planners.NAMES}' (a test checks they agree). */
        @AttributeDefinition(name = "Algorithm", description = "Path planner.", options = {
                @Option(label = "LPN", value = "lpn"), @Option(label = "LPN bounded", value = "lpn-bounded"),
                @Option(label = "LPN focused", value = "lpn-focused"),
                @Option(label = "LPN incremental", value = "lpn-incremental"),
                @Option(label = "Reference (A*)", value = "reference"), @Option(label = "Dijkstra", value = "dijkstra") })
        String algorithm() default LoopDefaults.PLANNER_ALGORITHM;

        /** No helper thread competes with the control loop for the robot's CPU. */
        @AttributeDefinition(name = "Threads", description = "Threads of the navigation function: accepted for old "
                + "configurations; every planner computes on the calling thread.", min = "1", max = "2")
        int threads() default LoopDefaults.PLANNER_THREADS;

        @AttributeDefinition(name = "Robot radius", description = "Radius of the robot footprint, m: cells closer to "
                + "an obstacle are impassable.", min = "0.01", max = "5")
        double robotRadius() default LoopDefaults.ROBOT_RADIUS;

        @AttributeDefinition(name = "Inflation radius", description = "Distance over which obstacle cost decays, m.",
                min = "0.01", max = "10")
        double inflationRadius() default LoopDefaults.INFLATION_RADIUS;

        @AttributeDefinition(name = "Blocked timeout", description = "Seconds the robot waits for a way around a "
                + "blocked path before the mission fails.", min = "0.5", max = "600")
        double blockedTimeout() default LoopDefaults.BLOCKED_TIMEOUT;
    }

    private NavigationPlanner planner;
    private Config config;
    private List<MapLandmark> landmarks;
    private List<Point2D> docks;
    private List<Passage> passages;

    @Activate
    void activate(Config c) throws IOException {
        this.config = c;
        MapServerFormat.LoadedMap loaded = MapServerFormat.load(Path.of(c.map()));
        landmarks = MapServerFormat.readLandmarks(Path.of(c.map()));
        docks = MapServerFormat.readDocks(Path.of(c.map()));
        passages = MapServerFormat.readPassages(Path.of(c.map()));
        planner = new NavigationPlanner(loaded.grid(), c.algorithm(), c.threads(), c.robotRadius(),
                c.inflationRadius());
    }

    @Deactivate
    void deactivate() {
        planner.close();
    }

    /** @return the planner over the configured map */
    NavigationPlanner planner() {
        return planner;
    }

    /** @return the ceiling landmarks the map names (its {@code sabot_landmarks} file), possibly none */
    List<MapLandmark> landmarks() {
        return landmarks;
    }

    /** @return the narrow passages the map lists (its {@code sabot_passages}), possibly none */
    List<Passage> passages() {
        return passages;
    }

    /** @return the charging docks the map lists (its {@code sabot_docks}), possibly none */
    List<Point2D> docks() {
        return docks;
    }

    /** @return the configured settings */
    Config config() {
        return config;
    }

    @Override
    public String name() {
        return "planner";
    }

    @Override
    public String status() {
        return planner.algorithm() + " on " + config.map() + " (" + planner.map().width() + " x "
                + planner.map().height() + " cells of " + planner.map().resolution() + " m)";
    }
}
