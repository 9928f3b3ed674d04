package sabot.controlml.payload;

import java.time.Instant;
import java.util.List;
import java.util.Objects;

/**
 * {@code cm.obstacles}: what the sensors see.
 *
 * @param time      when; never null
 * @param obstacles the discs; never null
 */
public record Obstacles(Instant time, List<Obstacle> obstacles) {
    public Obstacles {
        Objects.requireNonNull(time, "time");
        obstacles = List.copyOf(obstacles);
    }
}
