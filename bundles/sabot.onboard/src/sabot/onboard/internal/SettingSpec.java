package sabot.onboard.internal;

import java.util.List;
import java.util.Locale;

import org.eclipse.equinox.metatype.EquinoxAttributeDefinition;
import org.osgi.service.metatype.AttributeDefinition;

/**
 * What a task accepts for one setting: its type, bounds and options, as declared in the task's Metatype description.
 *
 * @param id   the setting's id (the part after {@code <task>.} in the configuration file)
 * @param type one of {@link AttributeDefinition#INTEGER}, {@link AttributeDefinition#LONG},
 *             {@link AttributeDefinition#DOUBLE}, {@link AttributeDefinition#BOOLEAN},
 *             {@link AttributeDefinition#STRING}
 * @param min  inclusive lower bound for numbers, or null
 * @param max  inclusive upper bound for numbers, or null
 * @param mandatory true when the file must set it: Metatype {@code required} and no default
 * @param options   the values it may take, as written in the file; empty: any value of its type and bounds
 */
public record SettingSpec(String id, int type, Double min, Double max, boolean mandatory, List<String> options) {

    public SettingSpec {
        options = List.copyOf(options);
    }

    /** A setting without options. */
    public SettingSpec(String id, int type, Double min, Double max, boolean mandatory) {
        this(id, type, min, max, mandatory, List.of());
    }

    /** A setting without options that the file may leave out. */
    public SettingSpec(String id, int type, Double min, Double max) {
        this(id, type, min, max, false);
    }

    /**
     * @param required whether the OCD lists the attribute among its required ones
     * @return the spec of a Metatype attribute definition (bounds read through Equinox's extension)
     */
    public static SettingSpec of(AttributeDefinition ad, boolean required) {
        Double min = null;
        Double max = null;
        if (ad instanceof EquinoxAttributeDefinition eq) {
            min = parseBound(eq.getMin());
            max = parseBound(eq.getMax());
        }
        String[] defaults = ad.getDefaultValue();
        String[] options = ad.getOptionValues();
        return new SettingSpec(ad.getID(), ad.getType(), min, max, required && (defaults == null
                || defaults.length == 0), options == null ? List.of() : List.of(options));
    }

    private static Double parseBound(String bound) {
        if (bound == null || bound.isBlank()) {
            return null;
        }
        try {
            return Double.valueOf(bound.strip());
        } catch (NumberFormatException e) {
            return null; // a non-numeric bound (string length) does not apply to numbers
        }
    }

    /**
     * Converts a value as written in the file into the type the task's configuration expects.
     *
     * @throws IllegalArgumentException with a message for the operator when the value does not fit
     */
    public Object convert(String text) {
        String v = text.strip();
        Object value;
        switch (type) {
            case AttributeDefinition.INTEGER, AttributeDefinition.LONG -> {
                long n;
                try {
                    n = Long.parseLong(v);
                } catch (NumberFormatException e) {
                    throw new IllegalArgumentException("'" + v + "' is not an integer");
                }
                checkRange(n, v);
                if (type == AttributeDefinition.LONG) {
                    value = Long.valueOf(n); // (a ?: between Integer and Long would unbox and widen to Long)
                } else if (n < Integer.MIN_VALUE || n > Integer.MAX_VALUE) {
                    throw new IllegalArgumentException("'" + v + "' is out of the integer range");
                } else {
                    value = Integer.valueOf((int) n);
                }
            }
            case AttributeDefinition.DOUBLE, AttributeDefinition.FLOAT -> {
                double d;
                try {
                    d = Double.parseDouble(v);
                } catch (NumberFormatException e) {
                    throw new IllegalArgumentException("'" + v + "' is not a number");
                }
                if (!Double.isFinite(d)) {
                    throw new IllegalArgumentException("'" + v + "' is not a finite number");
                }
                checkRange(d, v);
                if (type == AttributeDefinition.DOUBLE) {
                    value = Double.valueOf(d);
                } else {
                    value = Float.valueOf((float) d);
                }
            }
            case AttributeDefinition.BOOLEAN -> {
                String b = v.toLowerCase(Locale.ROOT);
                if (!b.equals("true") && !b.equals("false")) {
                    throw new IllegalArgumentException("'" + v + "' is not true or false");
                }
                value = Boolean.valueOf(b);
            }
            case AttributeDefinition.STRING -> value = v;
            default -> throw new IllegalArgumentException("setting type " + type + " is not supported in the file");
        }
        if (!options.isEmpty() && !options.contains(v)) {
            throw new IllegalArgumentException("'" + v + "' is not one of " + String.join(", ", options));
        }
        return value;
    }

    private void checkRange(double n, String text) {
        if (min != null && n < min) {
            throw new IllegalArgumentException("'" + text + "' is below the minimum " + fmt(min));
        }
        if (max != null && n > max) {
            throw new IllegalArgumentException("'" + text + "' is above the maximum " + fmt(max));
        }
    }

    private static String fmt(double d) {
        return d == Math.rint(d) ? Long.toString((long) d) : Double.toString(d);
    }
}
