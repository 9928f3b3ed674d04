package sabot.controlml.swe;

import java.util.Map;
import java.util.OptionalDouble;

/**
 * The UCUM unit codes ControlML uses, and the few alternative codes it converts from.
 * <p>
 * Every quantity of a payload has a canonical SI code (what ControlML writes). A reader accepts the canonical code
 * or a code of the same dimension listed here (e.g. {@code cm} or {@code mm} for {@code m}, {@code deg} for
 * {@code rad}) and converts; anything else, including codes of another dimension, is a wrong unit. The table is
 * deliberately small: only linear conversions a robot's operator is likely to type.
 */
public final class Ucum {

    private static final double DEG = Math.PI / 180.0;

    // canonical code -> (accepted code -> factor such that canonical value = value * factor)
    private static final Map<String, Map<String, Double>> CONVERSIONS = Map.ofEntries(
            Map.entry("m", Map.of("m", 1.0, "cm", 0.01, "mm", 0.001, "km", 1000.0)),
            Map.entry("rad", Map.of("rad", 1.0, "deg", DEG, "mrad", 0.001)),
            Map.entry("s", Map.of("s", 1.0, "ms", 0.001, "min", 60.0)),
            Map.entry("m/s", Map.of("m/s", 1.0, "cm/s", 0.01, "mm/s", 0.001, "km/h", 1000.0 / 3600.0)),
            Map.entry("rad/s", Map.of("rad/s", 1.0, "deg/s", DEG)),
            Map.entry("m/s2", Map.of("m/s2", 1.0, "cm/s2", 0.01, "mm/s2", 0.001)),
            Map.entry("rad/s2", Map.of("rad/s2", 1.0, "deg/s2", DEG)),
            Map.entry("m2", Map.of("m2", 1.0, "cm2", 1e-4, "mm2", 1e-6)),
            Map.entry("m.rad", Map.of("m.rad", 1.0)),
            Map.entry("rad2", Map.of("rad2", 1.0)),
            Map.entry("%", Map.of("%", 1.0, "1", 100.0)),
            Map.entry("1", Map.of("1", 1.0)),
            Map.entry("By", Map.of("By", 1.0)),
            Map.entry("Hz", Map.of("Hz", 1.0, "/s", 1.0, "/min", 1.0 / 60.0)),
            Map.entry("V", Map.of("V", 1.0, "mV", 0.001)),
            Map.entry("A", Map.of("A", 1.0, "mA", 0.001)),
            Map.entry("A.h", Map.of("A.h", 1.0, "mA.h", 0.001)));

    private Ucum() {
    }

    /**
     * Converts a value into a canonical unit.
     *
     * @param value     the value as written
     * @param code      the UCUM code it was written in
     * @param canonical the canonical code the payload field expects (one of the table's keys)
     * @return the value in the canonical unit, or empty when {@code code} is not a known code of that dimension
     */
    public static OptionalDouble toCanonical(double value, String code, String canonical) {
        Map<String, Double> accepted = CONVERSIONS.get(canonical);
        if (accepted == null) {
            throw new IllegalArgumentException("not a canonical ControlML unit: " + canonical);
        }
        Double factor = accepted.get(code);
        return factor == null ? OptionalDouble.empty() : OptionalDouble.of(factor == 1.0 ? value : value * factor);
    }

    /** @return true when {@code canonical} is one of ControlML's canonical unit codes */
    public static boolean isCanonical(String canonical) {
        return CONVERSIONS.containsKey(canonical);
    }
}
