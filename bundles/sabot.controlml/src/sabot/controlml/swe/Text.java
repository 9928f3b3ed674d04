package sabot.controlml.swe;

import java.util.Objects;

/** @param value free text; never null, may be empty */
public record Text(String value) implements SweComponent {

    public Text {
        Objects.requireNonNull(value, "value");
    }

    @Override
    public String elementName() {
        return "Text";
    }
}
