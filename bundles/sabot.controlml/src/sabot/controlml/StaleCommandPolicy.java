package sabot.controlml;

import java.time.Duration;
import java.util.Objects;

/**
 * What a device does with a set by its age: since its send time ({@code sent} on the requester's clock, moved by
 * the measured clock offset) or since the server held it (XEP-0203 delay stamp). Sets older than {@code maxAge}, or
 * sent more than {@code maxAge} ahead of the device's clock, are refused with {@link ControlMlCondition#STALE_COMMAND}, or applied anyway when
 * {@code refuse} is false. Gets are never stale.
 *
 * @param maxAge oldest acceptable command; never null, not negative
 * @param refuse true to refuse stale commands
 */
public record StaleCommandPolicy(Duration maxAge, boolean refuse) {

    /** The default: refuse sets older than {@link ControlMl#DEFAULT_STALE_COMMAND_S}. */
    public static final StaleCommandPolicy DEFAULT = new StaleCommandPolicy(Duration.ofSeconds(
            ControlMl.DEFAULT_STALE_COMMAND_S), true);

    public StaleCommandPolicy {
        Objects.requireNonNull(maxAge, "maxAge");
        if (maxAge.isNegative()) {
            throw new IllegalArgumentException("negative maxAge");
        }
    }

    /** @return a policy refusing sets older than {@code maxAge} */
    public static StaleCommandPolicy refuseOlderThan(Duration maxAge) {
        return new StaleCommandPolicy(maxAge, true);
    }

    /** @return a policy that applies commands whatever their age */
    public static StaleCommandPolicy applyAll() {
        return new StaleCommandPolicy(Duration.ZERO, false);
    }

    /** @return true when a set of this age must be refused */
    public boolean isStale(Duration age) {
        return refuse && age.compareTo(maxAge) > 0;
    }
}
