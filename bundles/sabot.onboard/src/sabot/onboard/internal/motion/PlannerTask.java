package sabot.onboard.internal.motion;

import java.io.IOException;
import java.nio.file.Path;
import java.util.List;

import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;
import org.osgi.service.component.annotations.Deactivate;

import sabot.model.map.MapLandmark;
import sabot.model.map.MapServerFormat;
import sabot.onboard.task.OnboardTask;

/**
 * Task {@code planner}: the map (ROS map_server YAML + image) and the path planner (LPN by default; any name of
 * {@code sabot.planner.Planners}). Swapping the algorithm is a configuration change. Settings:
 * OSGI-INF/metatype/planner.xml.
 */
@Component(name = "sabot.task.planner", configurationPolicy = ConfigurationPolicy.REQUIRE,
        service = { OnboardTask.class, PlannerTask.class })
public final class PlannerTask implements OnboardTask {

    /** Settings (names match the Metatype description). */
    public @interface Config {
        /** @return the map's YAML file (ROS map_server format) */
        String map();

        /** @return planner name: lpn, lpn-bounded, lpn-incremental, reference, dijkstra */
        String algorithm() default "lpn";

        /**
         * @return threads of the navigation function: 1 or 2 accepted, every planner computes on the calling thread
         *         (no helper thread competes with the control loop for the robot's CPU)
         */
        int threads() default 1;

        /** @return the robot's radius (footprint disc), m: cells closer to an obstacle are impassable */
        double robotRadius() default 0.25;

        /** @return distance over which obstacle cost decays, m */
        double inflationRadius() default 0.55;

        /** @return seconds the planner keeps retrying when the path is blocked before the mission fails */
        double blockedTimeout() default 10;
    }

    private NavigationPlanner planner;
    private Config config;
    private List<MapLandmark> landmarks;

    @Activate
    void activate(Config c) throws IOException {
        this.config = c;
        MapServerFormat.LoadedMap loaded = MapServerFormat.load(Path.of(c.map()));
        landmarks = MapServerFormat.readLandmarks(Path.of(c.map()));
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
