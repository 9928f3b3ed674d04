package sabot.workbench.statistics.internal;

import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.TreeMap;
import java.util.function.Function;

import sabot.controlml.ControlMlCondition;
import sabot.fleet.ServerFigures;
import sabot.workbench.fleet.TrafficStatistics;

/** What the Traffic view writes (plain Java: no SWT): its table's columns and the server's line. */
final class TrafficTexts {

    /** A column of the table: title, width in pixels, text of a snapshot. */
    record Column(String title, int width, Function<TrafficStatistics, String> text) {
    }

    static final List<Column> COLUMNS = List.of(
            new Column("Robot", 170, TrafficStatistics::robot),
            new Column("In msg/s", 80, s -> rate(s.stanzasInPerSecond())),
            new Column("Out msg/s", 85, s -> rate(s.stanzasOutPerSecond())),
            new Column("In B/s", 80, s -> bytes(s.bytesInPerSecond())),
            new Column("Out B/s", 80, s -> bytes(s.bytesOutPerSecond())),
            new Column("Requests", 80, s -> Long.toString(s.requests())),
            new Column("Errors", 300, TrafficTexts::errors),
            new Column("RTT p50 ms", 95, s -> ms(s.roundTripP50Ms())),
            new Column("RTT p99 ms", 95, s -> ms(s.roundTripP99Ms())),
            new Column("Telemetry Hz", 105, s -> rate(s.telemetryHz())),
            new Column("Age s", 60, s -> Double.isNaN(s.telemetryAgeS()) ? "–" : String.format(Locale.ROOT, "%.1f",
                    s.telemetryAgeS())));

    private TrafficTexts() {
    }

    /** "3: access-denied 1, timeout 2", or "0". */
    static String errors(TrafficStatistics s) {
        if (s.errors().isEmpty()) {
            return "0";
        }
        StringBuilder b = new StringBuilder().append(s.errorCount()).append(": ");
        String sep = "";
        for (Map.Entry<ControlMlCondition, Long> e : new TreeMap<>(s.errors()).entrySet()) {
            b.append(sep).append(e.getKey().element()).append(' ').append(e.getValue());
            sep = ", ";
        }
        return b.toString();
    }

    /** The server's figures of a robot as one line. */
    static String server(ServerFigures f) {
        StringBuilder b = new StringBuilder(String.format(Locale.ROOT, "server's archive, last %d min: %d requests, %d"
                + " answers, %d errors", f.window().toMinutes(), f.requests(), f.answers(), f.errors()));
        if (!f.errorsByCondition().isEmpty()) {
            b.append(" (");
            String sep = "";
            for (Map.Entry<String, Long> e : new TreeMap<>(f.errorsByCondition()).entrySet()) {
                b.append(sep).append(e.getKey()).append(' ').append(e.getValue());
                sep = ", ";
            }
            b.append(')');
        }
        if (f.answered() > 0) {
            b.append(String.format(Locale.ROOT, ", answer p50 %.1f ms p99 %.1f ms", f.answerP50Ms(), f.answerP99Ms()));
        }
        b.append(String.format(Locale.ROOT, ", telemetry %.2f Hz", f.telemetryHz()));
        if (!Double.isNaN(f.telemetryAgeS())) {
            b.append(String.format(Locale.ROOT, " (last %.1f s ago)", f.telemetryAgeS()));
        }
        return b.append(String.format(Locale.ROOT, ", %d session(s) now", f.sessions())).toString();
    }

    private static String rate(double perSecond) {
        return String.format(Locale.ROOT, "%.1f", perSecond);
    }

    private static String bytes(double perSecond) {
        return perSecond >= 10_000 ? String.format(Locale.ROOT, "%.1f k", perSecond / 1000) : String.format(
                Locale.ROOT, "%.0f", perSecond);
    }

    private static String ms(double ms) {
        return Double.isNaN(ms) ? "–" : String.format(Locale.ROOT, ms < 10 ? "%.2f" : "%.1f", ms);
    }
}
