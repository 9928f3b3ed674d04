package sabot.controlml.swe;

import java.time.Instant;
import java.util.Objects;

/**
 * A calendar time stamp, written as an ISO 8601 UTC date-time with the unit reference {@link Swe#ISO_8601_UOM}.
 *
 * @param value the instant (microsecond precision survives the round trip); never null
 */
public record Time(Instant value) implements SweComponent {

    public Time {
        Objects.requireNonNull(value, "value");
    }

    @Override
    public String elementName() {
        return "Time";
    }
}
