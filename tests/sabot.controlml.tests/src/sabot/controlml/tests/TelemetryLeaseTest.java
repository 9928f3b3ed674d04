package sabot.controlml.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.List;
import java.util.OptionalLong;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.internal.LeaseBook;
import sabot.controlml.payload.PayloadException;
import sabot.controlml.payload.RecordBuilder;
import sabot.controlml.payload.TelemetryRates;
import sabot.controlml.payload.TelemetryRates.StreamRate;
import sabot.controlml.swe.SweComponent;

/** Section 6's leases without a server: the book a device keeps, and the {@code cm.telemetry} record. */
class TelemetryLeaseTest {

    private static final long S = 1_000_000_000L;

    private static TelemetryRates ask(double lease, String resource, double hz) {
        return new TelemetryRates(lease, List.of(new StreamRate(resource, hz)));
    }

    private static LeaseBook book() {
        LeaseBook b = new LeaseBook(30);
        b.offer("cm.position", new LeaseBook.Offer(0.2, 10));
        b.offer("cm.mission", new LeaseBook.Offer(0.2, 1));
        return b;
    }

    @Test
    void unleasedResourcesArePublishedAtTheirBaseRate() {
        LeaseBook b = book();
        assertEquals(0.2, b.rate("cm.position"));
        assertEquals(0.2, b.rate("cm.mission"));
        assertEquals(0, b.rate("cm.obstacles"), "not offered");
        assertEquals(List.of("cm.position", "cm.mission"), b.offered());
        assertEquals(OptionalLong.empty(), b.nextExpiry());
    }

    @Test
    void aLeaseIsCutToTheFullRateAndTheLongestLease() {
        LeaseBook b = book();
        TelemetryRates granted = b.grant("wb@lab/a", new TelemetryRates(600, List.of(new StreamRate("cm.position",
                50), new StreamRate("cm.mission", 0.1))), 0);
        assertEquals(new TelemetryRates(30, List.of(new StreamRate("cm.position", 10), new StreamRate("cm.mission",
                0.2))), granted, "at most the full rate; never below the base, which is published anyway");
        assertEquals(10, b.rate("cm.position"));
        assertEquals(0.2, b.rate("cm.mission"));
        assertEquals(OptionalLong.of(30 * S), b.nextExpiry());
    }

    @Test
    void theHighestLeaseWinsAndEachWatcherReplacesOnlyItsOwn() {
        LeaseBook b = book();
        b.grant("wb@lab/a", ask(10, "cm.position", 1), 0);
        b.grant("wb@lab/b", ask(10, "cm.position", 5), 0);
        assertEquals(5, b.rate("cm.position"));
        b.grant("wb@lab/b", ask(10, "cm.position", 2), S); // b renews slower
        assertEquals(2, b.rate("cm.position"));
        assertEquals(2, b.watchers());
        b.grant("wb@lab/b", new TelemetryRates(0, List.of()), S); // b ends its lease
        assertEquals(1, b.rate("cm.position"));
        assertTrue(b.release("wb@lab/a"));
        assertFalse(b.release("wb@lab/a"));
        assertEquals(0.2, b.rate("cm.position"));
        assertEquals(0, b.watchers());
    }

    @Test
    void aLeaseEndsWhenItsTimeIsUp() {
        LeaseBook b = book();
        b.grant("wb@lab/a", ask(2, "cm.position", 10), 5 * S);
        b.grant("wb@lab/b", ask(4, "cm.position", 3), 5 * S);
        assertFalse(b.expire(7 * S - 1));
        assertEquals(OptionalLong.of(7 * S), b.nextExpiry());
        assertTrue(b.expire(7 * S));
        assertEquals(3, b.rate("cm.position"));
        b.grant("wb@lab/b", ask(4, "cm.position", 3), 8 * S); // renewed in time
        assertFalse(b.expire(9 * S + 1));
        assertTrue(b.expire(12 * S));
        assertEquals(0.2, b.rate("cm.position"));
    }

    @Test
    void aResourceTheDeviceDoesNotPublishIsGrantedZero() {
        LeaseBook b = book();
        TelemetryRates granted = b.grant("wb@lab/a", new TelemetryRates(10, List.of(new StreamRate("cm.obstacles", 5),
                new StreamRate("cm.position", 5))), 0);
        assertEquals(new TelemetryRates(10, List.of(new StreamRate("cm.obstacles", 0), new StreamRate("cm.position",
                5))), granted, "a watcher may ask every device for the same resources");
        assertEquals(0, b.rate("cm.obstacles"));
        assertEquals(new TelemetryRates(0, List.of(new StreamRate("cm.obstacles", 0))), b.grant("wb@lab/b",
                new TelemetryRates(10, List.of(new StreamRate("cm.obstacles", 5))), 0), "nothing leased: no lease");
        assertEquals(1, b.watchers());
    }

    @Test
    void aLeaseWithoutARateAboveZeroIsNoLease() {
        LeaseBook b = book();
        TelemetryRates granted = b.grant("wb@lab/a", ask(10, "cm.position", 0), 0);
        assertEquals(new TelemetryRates(0, List.of(new StreamRate("cm.position", 0.2))), granted);
        assertEquals(0, b.watchers());
        assertThrows(IllegalArgumentException.class, () -> new LeaseBook(0));
        assertThrows(IllegalArgumentException.class, () -> new LeaseBook.Offer(2, 1));
    }

    // ------------------------------------------------------------------------------------------------ the record

    @Test
    void theRecordTravelsAndAcceptsOtherUnitsOfFrequency() throws PayloadException {
        TelemetryRates r = new TelemetryRates(30, List.of(new StreamRate("cm.position", 10), new StreamRate(
                "cm.mission", 0.5)));
        assertEquals(r, TelemetryRates.CODEC.decode(TelemetryRates.CODEC.encode(r)));
        SweComponent perMinute = new RecordBuilder().quantity("lease", "min", 1).count("count", 1).add("stream0",
                new RecordBuilder().text("resource", "cm.position").quantity("rate", "/min", 30).build()).build();
        assertEquals(ask(60, "cm.position", 0.5), TelemetryRates.CODEC.decode(perMinute));
    }

    @ParameterizedTest(name = "{0}")
    @CsvSource(delimiter = '|', value = {
        "rate over 100 Hz           | 30 | cm.position | 101 | Hz | cm.mission  | invalid-value",
        "negative rate              | 30 | cm.position | -1  | Hz | cm.mission  | invalid-value",
        "rate in metres             | 30 | cm.position | 1   | m  | cm.mission  | wrong-unit",
        "not a resource name        | 30 | Position    | 1   | Hz | cm.mission  | invalid-value",
        "a resource twice           | 30 | cm.position | 1   | Hz | cm.position | invalid-value",
        "lease over an hour         | 3601 | cm.position | 1 | Hz | cm.mission  | invalid-value",
        "negative lease             | -1 | cm.position | 1   | Hz | cm.mission  | invalid-value",
    })
    void badRecordsAreRefused(String why, double lease, String resource, double rate, String unit, String second,
            String condition) {
        SweComponent bad = new RecordBuilder().quantity("lease", "s", lease).count("count", 2).add("stream0",
                new RecordBuilder().text("resource", resource).quantity("rate", unit, rate).build()).add("stream1",
                        new RecordBuilder().text("resource", second).quantity("rate", "Hz", 1).build()).build();
        PayloadException e = assertThrows(PayloadException.class, () -> TelemetryRates.CODEC.decode(bad), why);
        assertEquals(ControlMlCondition.fromElement(condition), e.error().cmCondition(), why + ": " + e.getMessage());
    }

    @Test
    void moreStreamsThanARecordHoldsAreRefused() {
        RecordBuilder b = new RecordBuilder().quantity("lease", "s", 1).count("count", 17);
        for (int i = 0; i < 17; i++) {
            b.add("stream" + i, new RecordBuilder().text("resource", "cm.r" + i).quantity("rate", "Hz", 1).build());
        }
        SweComponent many = b.build();
        PayloadException e = assertThrows(PayloadException.class, () -> TelemetryRates.CODEC.decode(many));
        assertEquals(ControlMlCondition.INVALID_VALUE, e.error().cmCondition());
        SweComponent missing = new RecordBuilder().count("count", 0).build();
        assertEquals(ControlMlCondition.MALFORMED_PAYLOAD, assertThrows(PayloadException.class,
                () -> TelemetryRates.CODEC.decode(missing)).error().cmCondition());
    }
}
