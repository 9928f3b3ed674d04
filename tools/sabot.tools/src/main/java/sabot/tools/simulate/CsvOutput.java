package sabot.tools.simulate;

import java.io.BufferedWriter;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Locale;

import sabot.motion.sim.Trace;

/** Writes a {@link Trace} as CSV: a header with units in the column names, one row per control step. */
public final class CsvOutput {

    private CsvOutput() {
    }

    public static void write(Trace t, Path file) throws IOException {
        try (BufferedWriter w = Files.newBufferedWriter(file, StandardCharsets.UTF_8)) {
            w.write(String.join(",", Trace.COLUMNS));
            w.write(",status\n");
            StringBuilder sb = new StringBuilder(256);
            for (int r = 0; r < t.size(); r++) {
                sb.setLength(0);
                for (int c = 0; c < Trace.COLUMNS.length; c++) {
                    double v = t.get(r, c);
                    sb.append(c == 0 ? String.valueOf((int) v) : String.format(Locale.ROOT, "%.6f", v)).append(',');
                }
                sb.append(t.status(r)).append('\n');
                w.write(sb.toString());
            }
        }
    }
}
