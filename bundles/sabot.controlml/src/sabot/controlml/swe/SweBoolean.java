package sabot.controlml.swe;

/** @param value a flag (SWE {@code Boolean}) */
public record SweBoolean(boolean value) implements SweComponent {

    @Override
    public String elementName() {
        return "Boolean";
    }
}
