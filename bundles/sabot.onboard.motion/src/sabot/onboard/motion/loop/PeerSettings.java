package sabot.onboard.motion.loop;

/**
 * How the loop treats the other robots (the {@code motion} task's {@code peer*} and {@code passage*} settings).
 *
 * @param memory          s another robot not heard from stays an obstacle and its passage claim counts
 * @param passageApproach m of the path ahead within which a passage of the map is asked for (the robot that yields
 *                        stops about this far short of it, less its braking distance)
 * @param passageTimeout  s a robot waits for its turn at a passage before its mission fails
 */
public record PeerSettings(double memory, double passageApproach, double passageTimeout) {

    /** @throws IllegalArgumentException naming the value that is not positive */
    public PeerSettings {
        if (!(memory > 0) || !(passageApproach > 0) || !(passageTimeout > 0)) {
            throw new IllegalArgumentException("peer memory, passage approach and passage timeout must be > 0, were "
                    + memory + " s, " + passageApproach + " m, " + passageTimeout + " s");
        }
    }
}
