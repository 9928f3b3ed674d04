package sabot.planner;

import org.osgi.annotation.versioning.ProviderType;

/**
 * The outcome of one planning request: a path, or the reason there is none. Never null, never a partial path.
 */
@ProviderType
public sealed interface PlanResult {

    /** @return true for {@link Found} */
    default boolean isFound() {
        return this instanceof Found;
    }

    /**
     * A path was found.
     *
     * @param path  the collision-free path from start to goal
     * @param field the planner's cost-to-goal; a view valid until the planner plans again
     */
    record Found(PlannedPath path, PotentialField field) implements PlanResult {
    }

    /**
     * No path exists (or the request is unusable).
     *
     * @param reason what prevents a path
     * @param detail a sentence for people: which point, which cell, how large the goal's region is
     */
    record Unreachable(UnreachableReason reason, String detail) implements PlanResult {
    }
}
