package sabot.onboard.task;

import java.util.Map;

/**
 * Typed reads of a task's configuration properties with the task's defaults. Values come typed from the onboard
 * application (Metatype types) or from any Config Admin client, so numbers are accepted as any {@link Number} or as
 * text.
 */
public final class TaskProperties {

    private final Map<String, ?> properties;

    public TaskProperties(Map<String, ?> properties) {
        this.properties = properties;
    }

    /** @return true when the property is set (and not blank) */
    public boolean has(String key) {
        Object v = properties.get(key);
        return v != null && !v.toString().isBlank();
    }

    /** @return the property as text, stripped, or {@code fallback} when absent */
    public String string(String key, String fallback) {
        Object v = properties.get(key);
        return v == null ? fallback : v.toString().strip();
    }

    /** @throws IllegalArgumentException when the value is not a number */
    public double number(String key, double fallback) {
        Object v = properties.get(key);
        if (v == null) {
            return fallback;
        }
        if (v instanceof Number n) {
            return n.doubleValue();
        }
        try {
            return Double.parseDouble(v.toString().strip());
        } catch (NumberFormatException e) {
            throw new IllegalArgumentException("'" + v + "' is not a number");
        }
    }

    /** @throws IllegalArgumentException when the value is not an integer */
    public long integer(String key, long fallback) {
        Object v = properties.get(key);
        if (v == null) {
            return fallback;
        }
        if (v instanceof Integer || v instanceof Long || v instanceof Short || v instanceof Byte) {
            return ((Number) v).longValue();
        }
        try {
            return Long.parseLong(v.toString().strip());
        } catch (NumberFormatException e) {
            throw new IllegalArgumentException("'" + v + "' is not an integer");
        }
    }

    /** @throws IllegalArgumentException when the value is not true or false */
    public boolean bool(String key, boolean fallback) {
        Object v = properties.get(key);
        if (v == null) {
            return fallback;
        }
        if (v instanceof Boolean b) {
            return b;
        }
        String s = v.toString().strip();
        if (s.equalsIgnoreCase("true") || s.equalsIgnoreCase("false")) {
            return Boolean.parseBoolean(s);
        }
        throw new IllegalArgumentException("'" + v + "' is not true or false");
    }
}
