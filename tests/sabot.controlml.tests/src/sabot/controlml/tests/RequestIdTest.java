package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Clock;
import java.time.Instant;
import java.time.LocalDate;
import java.time.ZoneOffset;
import java.util.HashSet;
import java.util.Set;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import sabot.controlml.RequestId;
import sabot.controlml.RequestIdGenerator;

class RequestIdTest {

    @Test
    void wireFormIsDateColonCounter() {
        assertEquals("20261121:42", new RequestId(LocalDate.of(2026, 11, 21), 42).toString());
        assertEquals(new RequestId(LocalDate.of(2026, 1, 2), 4294967295L), RequestId.parse("20260102:4294967295"));
        assertEquals(new RequestId(LocalDate.of(2026, 1, 2), 0), RequestId.parse("20260102:0"));
    }

    @ParameterizedTest
    @ValueSource(strings = { "", "20261121", "20261121:", "20261121:-1", "20261121:+1", "20261121:01",
            "20261121:4294967296", "20261321:1", "20260230:1", "2026112:1", "2026-11-21:1", "20261121:1 ",
            "20261121:99999999999", "abcdefgh:1", "20261121;1", "20261121:1:2", "x20261121:1" })
    void malformedIdsAreRejected(String text) {
        assertNull(RequestId.parse(text), text);
    }

    @Test
    void generatorIssuesUniqueIncreasingIdsAndStartsAfterEarlierRunsOfTheSameDay() {
        Instant morning = Instant.parse("2026-11-21T08:00:00Z");
        RequestIdGenerator first = new RequestIdGenerator(Clock.fixed(morning, ZoneOffset.UTC));
        Set<RequestId> seen = new HashSet<>();
        RequestId last = null;
        for (int i = 0; i < 10_000; i++) {
            RequestId id = first.next();
            assertTrue(seen.add(id));
            assertTrue(last == null || id.compareTo(last) > 0);
            last = id;
        }
        // a restart one second later does not reuse the ids of the first run
        RequestIdGenerator restarted = new RequestIdGenerator(Clock.fixed(morning.plusSeconds(1), ZoneOffset.UTC));
        assertTrue(restarted.next().compareTo(last) > 0);
    }

    @Test
    void generatorDatesIdsInUtcAndRestartsAtMidnight() {
        RequestIdGenerator g = new RequestIdGenerator(Clock.fixed(Instant.parse("2026-11-21T23:59:59.999Z"),
                ZoneOffset.UTC));
        RequestId late = g.next();
        assertEquals(LocalDate.of(2026, 11, 21), late.date());
        assertTrue(late.counter() <= RequestId.MAX_COUNTER);
        RequestIdGenerator next = new RequestIdGenerator(Clock.fixed(Instant.parse("2026-11-22T00:00:00Z"),
                ZoneOffset.UTC));
        assertEquals(new RequestId(LocalDate.of(2026, 11, 22), 0), next.next());
    }
}
