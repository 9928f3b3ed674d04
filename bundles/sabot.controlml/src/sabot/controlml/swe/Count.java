package sabot.controlml.swe;

/** @param value an integer count (SWE {@code Count}, an xs:integer; ControlML limits it to a Java long) */
public record Count(long value) implements SweComponent {

    @Override
    public String elementName() {
        return "Count";
    }
}
