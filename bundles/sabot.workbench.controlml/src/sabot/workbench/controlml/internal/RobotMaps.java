package sabot.workbench.controlml.internal;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.nio.file.Path;
import java.util.Map;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CompletionException;
import java.util.concurrent.ConcurrentHashMap;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.Resources;
import sabot.controlml.payload.GridMap;
import sabot.model.map.MapServerFormat;
import sabot.model.map.OccupancyGrid;
import sabot.workbench.fleet.FleetCommandException;
import sabot.workbench.fleet.FleetState;

/**
 * The robots' maps, fetched once per robot and connection: with {@code cm.map}, or, when the map does not fit a
 * payload, from the robot's remote files ({@link #MAP_FILE} and the image it names), read into memory.
 */
final class RobotMaps {

    /**
     * Where a robot keeps its map for workbenches when {@code cm.map} cannot carry it (a payload holds at most 64 KiB
     * of characters, about 30,000 cells: the lab's 240 x 180 grid does not fit): a ROS map_server YAML at the root
     * of its remote files, its image beside it.
     */
    static final String MAP_FILE = "map.yaml";

    private final FleetState fleet;
    private final Map<String, CompletableFuture<GridMap>> maps = new ConcurrentHashMap<>();

    RobotMaps(FleetState fleet) {
        this.fleet = fleet;
    }

    /** @return the robot's map; a failed fetch is not kept: the next call asks again */
    CompletableFuture<GridMap> map(String robot) {
        CompletableFuture<GridMap> f = maps.computeIfAbsent(robot, r -> fleet.get(r, Resources.MAP)
                .exceptionallyCompose(e -> {
                    FleetCommandException refused = FleetCommandException.in(e);
                    return refused != null && refused.condition() == ControlMlCondition.PAYLOAD_TOO_LARGE
                            ? fromFiles(r) : CompletableFuture.failedFuture(e);
                }));
        f.whenComplete((m, e) -> {
            if (e != null) {
                maps.remove(robot, f);
            }
        });
        return f;
    }

    /** Forgets every map (the connection changed). */
    void clear() {
        maps.clear();
    }

    /** The map from the robot's remote files: the YAML, then the image it names, each read whole into memory. */
    private CompletableFuture<GridMap> fromFiles(String robot) {
        Path yamlName = Path.of(robot, MAP_FILE); // what the errors name
        return read(robot, MAP_FILE).thenCompose(yaml -> {
            String image = parse(robot, () -> MapServerFormat.readMetadata(yamlName, yaml).image());
            if (image.contains("/") || image.startsWith(".")) {
                throw new FleetCommandException(ControlMlCondition.INVALID_VALUE, robot + "'s " + MAP_FILE
                        + " names an image outside its folder: " + image);
            }
            return read(robot, image).thenApply(pgm -> {
                OccupancyGrid g = parse(robot, () -> MapServerFormat.load(yamlName, yaml, pgm).grid());
                return new GridMap(g.resolution(), g.width(), g.height(), g.geometry().origin(), g.toArray());
            });
        }).exceptionallyCompose(e -> CompletableFuture.failedFuture(e instanceof CompletionException c && c
                .getCause() != null ? c.getCause() : e));
    }

    private CompletableFuture<byte[]> read(String robot, String path) {
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        return fleet.download(robot, path, 0, chunk -> out.writeBytes(chunk.data())).thenApply(done -> out
                .toByteArray());
    }

    @FunctionalInterface
    private interface Parse<T> {
        T run() throws IOException;
    }

    /** Runs a parse of the map's files; a malformed file is the robot's INVALID_VALUE. */
    private static <T> T parse(String robot, Parse<T> parse) {
        try {
            return parse.run();
        } catch (IOException e) {
            throw new FleetCommandException(ControlMlCondition.INVALID_VALUE, "map of " + robot + " from its files: "
                    + e.getMessage());
        }
    }
}
