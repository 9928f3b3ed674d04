package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import java.time.Instant;
import java.time.format.DateTimeParseException;
import java.util.SplittableRandom;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import sabot.controlml.swe.IsoInstant;

/** The time-stamp fast path gives exactly what the JDK's Instant.parse / Instant.toString give. */
class IsoInstantTest {

    @Test
    void agreesWithTheJdkOnRandomInstants() {
        SplittableRandom random = new SplittableRandom(20261121);
        long first = Instant.parse("0000-01-01T00:00:00Z").getEpochSecond();
        long last = Instant.parse("9999-12-31T23:59:59Z").getEpochSecond();
        for (int i = 0; i < 200_000; i++) {
            int nano = switch (i % 4) {
                case 0 -> 0;
                case 1 -> random.nextInt(1000) * 1_000_000;
                case 2 -> random.nextInt(1_000_000) * 1_000;
                default -> random.nextInt(1_000_000_000);
            };
            Instant instant = Instant.ofEpochSecond(random.nextLong(first, last + 1), nano);
            StringBuilder out = new StringBuilder();
            IsoInstant.format(instant, out);
            assertEquals(instant.toString(), out.toString());
            assertEquals(instant, IsoInstant.parse(out));
        }
    }

    @ParameterizedTest
    @ValueSource(strings = { "2026-11-21T10:15:30Z", "2026-11-21T10:15:30.1Z", "2026-11-21T10:15:30.123456789Z",
        "2024-02-29T00:00:00Z", "0000-01-01T00:00:00Z", "9999-12-31T23:59:59.999999999Z", "1969-12-31T23:59:59.5Z",
        "2026-11-21T10:15:30+01:00", "2026-11-21T10:15:30.25-05:30", "2026-06-30T23:59:60Z", "+10000-01-01T00:00:00Z",
        "-0001-01-01T00:00:00Z", "2026-11-21T10:15:30.Z", "2026-11-21T24:00:00Z" })
    void parsesWhatTheJdkParses(String text) {
        assertEquals(Instant.parse(text), IsoInstant.parse(text));
    }

    @ParameterizedTest
    @ValueSource(strings = { "", "2026-11-21", "2026-11-21T10:15:30", "2026-02-29T00:00:00Z",
        "2026-13-01T00:00:00Z", "2026-11-31T00:00:00Z", "2026-11-21T10:60:00Z",
        "2026-11-21T10:15:61Z", "2026-11-21T10:15:30.1234567890Z", "2026-11-21 10:15:30Z", "2026-1a-21T10:15:30Z",
        "2026-11-21T10:15:30.12a4Z", "2026-11-21T10:15:3OZ" })
    void refusesWhatTheJdkRefuses(String text) {
        assertThrows(DateTimeParseException.class, () -> Instant.parse(text));
        assertThrows(DateTimeParseException.class, () -> IsoInstant.parse(text));
    }

    @Test
    void writesOtherYearsLikeTheJdk() {
        for (String text : new String[] { "+10000-01-01T00:00:00Z", "-0001-12-31T23:59:59.5Z" }) {
            Instant instant = Instant.parse(text);
            StringBuilder out = new StringBuilder();
            IsoInstant.format(instant, out);
            assertEquals(instant.toString(), out.toString());
        }
    }
}
