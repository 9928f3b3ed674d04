package sabot.controlml.swe;

import java.util.Objects;

/** @param value a code from a closed list, e.g. a mission state; never null */
public record Category(String value) implements SweComponent {

    public Category {
        Objects.requireNonNull(value, "value");
    }

    @Override
    public String elementName() {
        return "Category";
    }
}
