package sabot.workbench.controlml.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.charset.StandardCharsets;
import java.util.Map;
import java.util.Random;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

import sabot.controlml.ControlMlCondition;
import sabot.workbench.fleet.TrafficStatistics;

/**
 * The traffic counters' algorithms on a clock the test advances: rates over a window of complete seconds, percentiles
 * of round trips in bounded memory, a robot's snapshot.
 */
class TrafficCountersTest {

    private static final long S = 1_000_000_000L;
    private static final long MS = 1_000_000L;
    /** An arbitrary monotonic origin, not a multiple of a second (System.nanoTime's origin is arbitrary too). */
    private static final long T0 = 7_123_456_789L;

    @Test
    void rateOfASteadyStreamIsExactOnceTheWindowIsFull() {
        RateWindow w = new RateWindow(10, T0);
        for (int i = 0; i < 30 * 25; i++) { // 25 Hz for 30 s, 100 bytes each
            w.add(T0 + i * (S / 25), 100);
        }
        long now = T0 + 30 * S;
        assertEquals(25.0, w.eventsPerSecond(now), 1e-9);
        assertEquals(2500.0, w.amountPerSecond(now), 1e-9);
        assertEquals(750, w.totalEvents());
        assertEquals(75_000, w.totalAmount());
    }

    @Test
    void rateCountsOnlyCompleteSecondsSinceTheStart() {
        RateWindow w = new RateWindow(10, 0);
        for (int i = 0; i < 5; i++) {
            w.add(2 * S + i * (S / 5), 1); // 5 events within second 2
        }
        assertEquals(0.0, w.eventsPerSecond(2 * S + S / 2), 1e-9, "second 2 is not complete yet");
        // at 3.0 s three complete seconds (0, 1, 2) of which one had 5 events
        assertEquals(5.0 / 3, w.eventsPerSecond(3 * S), 1e-9);
        assertEquals(0.0, new RateWindow(10, 0).eventsPerSecond(0), "no complete second: 0, not NaN");
    }

    @Test
    void rateForgetsSecondsThatLeftTheWindow() {
        RateWindow w = new RateWindow(10, 0);
        for (int i = 0; i < 100; i++) {
            w.add(i * (S / 10), 0); // 10 Hz during the first 10 s, then silence
        }
        assertEquals(10.0, w.eventsPerSecond(10 * S), 1e-9);
        assertEquals(5.0, w.eventsPerSecond(15 * S), 1e-9, "half the window silent");
        assertEquals(0.0, w.eventsPerSecond(20 * S), 1e-9);
        assertEquals(0.0, w.eventsPerSecond(1000 * S), 1e-9, "a bucket reused much later is not counted");
        assertEquals(100, w.totalEvents(), "the totals keep everything");
    }

    @Test
    void rateWindowRefusesABadLength() {
        assertEquals("a rate window of 0 s: expected 1..3600 s", assertThrows(IllegalArgumentException.class,
                () -> new RateWindow(0, 0)).getMessage());
    }

    @Test
    void percentilesOfKnownDurationsAreWithinTheBucketError() {
        LatencyWindow w = new LatencyWindow(6, 10);
        for (int ms = 1; ms <= 100; ms++) { // 1..100 ms: p50 is 50 ms, p99 is 99 ms (nearest rank)
            w.add(T0, ms * MS);
        }
        assertEquals(100, w.count(T0));
        assertEquals(50 * MS, w.quantileNanos(0.5, T0), 50 * MS * LatencyWindow.RELATIVE_ERROR);
        assertEquals(99 * MS, w.quantileNanos(0.99, T0), 99 * MS * LatencyWindow.RELATIVE_ERROR);
        assertEquals(100 * MS, w.quantileNanos(1.0, T0), 100 * MS * LatencyWindow.RELATIVE_ERROR);
    }

    @Test
    void percentilesOfRandomDurationsMatchTheSortedSample() {
        Random random = new Random(33);
        LatencyWindow w = new LatencyWindow(6, 10);
        long[] sample = new long[10_000];
        for (int i = 0; i < sample.length; i++) {
            sample[i] = (long) (Math.exp(random.nextGaussian() * 0.8) * 3 * MS); // log-normal around 3 ms
            w.add(T0, sample[i]);
        }
        java.util.Arrays.sort(sample);
        for (double q : new double[] {0.5, 0.9, 0.99}) {
            long exact = sample[(int) Math.ceil(q * sample.length) - 1];
            assertEquals(exact, w.quantileNanos(q, T0), exact * LatencyWindow.RELATIVE_ERROR, "q " + q);
        }
    }

    @Test
    void percentilesCoverOnlyTheWindow() {
        LatencyWindow w = new LatencyWindow(6, 10); // the last 60 s
        w.add(T0, 500 * MS); // one slow answer, then fast ones
        for (int i = 1; i <= 99; i++) {
            w.add(T0 + 30 * S, 2 * MS);
        }
        assertTrue(w.quantileNanos(1.0, T0 + 30 * S) > 400 * MS, "the slow one is in the window");
        assertEquals(2 * MS, w.quantileNanos(1.0, T0 + 65 * S), 2 * MS * LatencyWindow.RELATIVE_ERROR,
                "65 s later the slow one has left it");
        assertEquals(99, w.count(T0 + 65 * S));
        assertTrue(Double.isNaN(w.quantileNanos(0.5, T0 + 200 * S)), "an empty window has no percentile");
    }

    @Test
    void durationsOutsideTheRangeAreClampedNotLost() {
        LatencyWindow w = new LatencyWindow(1, 60);
        w.add(T0, 0);
        w.add(T0, Long.MAX_VALUE);
        assertEquals(2, w.count(T0));
        assertTrue(w.quantileNanos(0.5, T0) < 2 * LatencyWindow.MIN_NANOS);
        assertTrue(w.quantileNanos(1.0, T0) > LatencyWindow.MAX_NANOS / 2);
    }

    @ParameterizedTest
    @ValueSource(doubles = {0, -0.5, 1.5, Double.NaN})
    void aQuantileOutsideZeroToOneIsRefused(double q) {
        LatencyWindow w = new LatencyWindow(1, 60);
        assertEquals("quantile " + q + ": expected 0 < q <= 1", assertThrows(IllegalArgumentException.class,
                () -> w.quantileNanos(q, T0)).getMessage());
    }

    @Test
    void robotSnapshotCountsTrafficRequestsErrorsAndTelemetry() {
        RobotTraffic t = new RobotTraffic("sabot-01@sabot.local", T0);
        for (int i = 0; i < 20 * 10; i++) { // 10 Hz of 300-byte telemetry for 20 s
            long at = T0 + i * (S / 10);
            t.received(at, 300);
            t.telemetry(at);
        }
        for (int i = 0; i < 20; i++) { // one 200-byte request a second, answered in 4 ms (the last four refused)
            long at = T0 + i * S;
            t.requested();
            t.sent(at, 200);
            t.answered(at + 4 * MS, 4 * MS, i < 16 ? null : ControlMlCondition.SET_NOT_PERMITTED);
        }
        t.requested();
        t.answered(T0 + 19 * S, 10 * S, ControlMlCondition.TIMEOUT); // not a round trip: no answer came
        long now = T0 + 20 * S + S / 10;
        TrafficStatistics s = t.snapshot(now);
        assertEquals(200, s.stanzasIn());
        assertEquals(60_000, s.bytesIn());
        assertEquals(10.0, s.stanzasInPerSecond(), 1e-9);
        assertEquals(3000.0, s.bytesInPerSecond(), 1e-9);
        assertEquals(20, s.stanzasOut());
        assertEquals(1.0, s.stanzasOutPerSecond(), 1e-9);
        assertEquals(200.0, s.bytesOutPerSecond(), 1e-9);
        assertEquals(21, s.requests());
        assertEquals(Map.of(ControlMlCondition.SET_NOT_PERMITTED, 4L, ControlMlCondition.TIMEOUT, 1L), s.errors());
        assertEquals(5, s.errorCount());
        assertEquals(20, s.roundTrips());
        assertEquals(4.0, s.roundTripP50Ms(), 4.0 * LatencyWindow.RELATIVE_ERROR);
        assertEquals(4.0, s.roundTripP99Ms(), 4.0 * LatencyWindow.RELATIVE_ERROR);
        assertEquals(200, s.telemetryItems());
        assertEquals(10.0, s.telemetryHz(), 1e-9);
        assertEquals(0.2, s.telemetryAgeS(), 1e-9, "the last item came at 19.9 s");
    }

    @Test
    void aRobotWithoutTelemetryOrAnswersHasNoAgeNorPercentiles() {
        TrafficStatistics s = new RobotTraffic("sabot-02@sabot.local", T0).snapshot(T0 + 5 * S);
        assertTrue(Double.isNaN(s.telemetryAgeS()));
        assertTrue(Double.isNaN(s.roundTripP50Ms()));
        assertTrue(Double.isNaN(s.roundTripP99Ms()));
        assertEquals(0, s.roundTrips());
        assertEquals(Map.of(), s.errors());
    }

    @ParameterizedTest
    @ValueSource(strings = {"<iq/>", "<x>é</x>", "<x>€ Ω</x>", "<x>\uD83E\uDD16</x>", ""})
    void utf8LengthIsTheEncodedLength(String text) {
        assertEquals(text.getBytes(StandardCharsets.UTF_8).length, FleetTraffic.utf8Length(text));
    }

    /** A stanza as Smack builds it (nested XML builders, as the listeners count it): its encoded length. */
    @Test
    void aStanzasLengthIsItsEncodedXmlsLength() throws Exception {
        var inner = org.jivesoftware.smack.packet.StandardExtensionElement.builder("pose", "urn:example").addAttribute(
                "x", "1.5").addElement("note", "Ω € \uD83E\uDD16 <&>").build();
        var outer = org.jivesoftware.smack.packet.StandardExtensionElement.builder("event", "urn:example:event")
                .addElement(inner).addElement(inner).build();
        org.jivesoftware.smack.packet.Message m = org.jivesoftware.smack.packet.StanzaBuilder.buildMessage("m1").to(
                "sabot-01@sabot.local/onboard").setBody("é").addExtension(outer).build();
        CharSequence xml = m.toXML();
        assertTrue(xml instanceof org.jivesoftware.smack.util.XmlStringBuilder, xml.getClass().getName());
        assertEquals(xml.toString().getBytes(StandardCharsets.UTF_8).length, FleetTraffic.utf8Length(xml));
    }
}
