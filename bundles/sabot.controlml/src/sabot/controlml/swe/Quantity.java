package sabot.controlml.swe;

import java.util.Objects;

/**
 * A measured or commanded decimal value with its unit.
 *
 * @param uom   UCUM unit code (e.g. {@code m}, {@code rad/s}, {@code m2}); never null
 * @param value the value in {@code uom}; may be NaN or infinite as parsed ({@code NaN}, {@code INF} are legal
 *              xs:double lexical forms): payload codecs refuse non-finite values
 */
public record Quantity(String uom, double value) implements SweComponent {

    public Quantity {
        Objects.requireNonNull(uom, "uom");
    }

    @Override
    public String elementName() {
        return "Quantity";
    }
}
