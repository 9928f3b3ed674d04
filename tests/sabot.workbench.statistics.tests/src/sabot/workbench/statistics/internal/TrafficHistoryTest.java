package sabot.workbench.statistics.internal;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;

import java.time.Duration;
import java.util.Map;

import org.junit.jupiter.api.Test;

import sabot.controlml.ControlMlCondition;
import sabot.fleet.ServerFigures;
import sabot.workbench.fleet.TrafficStatistics;

/** The Traffic view's plot memory and texts (plain Java: no display). */
class TrafficHistoryTest {

    private static final String ROBOT = "sabot-01@sabot.local";

    private static TrafficStatistics snapshot(double in, double out, double p99) {
        return new TrafficStatistics(ROBOT, 0, 0, 0, 0, in, out, 0, 0, 0, Map.of(), 0, Double.NaN, p99, 0, 0,
                Double.NaN);
    }

    @Test
    void historyKeepsTheLastFiveMinutesOldestFirstRelativeToNow() {
        TrafficHistory h = new TrafficHistory();
        for (int t = 0; t < TrafficHistory.SAMPLES + 50; t++) {
            h.add(t, snapshot(t, 2 * t, 1));
        }
        assertEquals(TrafficHistory.SAMPLES, h.size(ROBOT));
        double now = TrafficHistory.SAMPLES + 49;
        double[][] in = h.series(ROBOT, TrafficHistory.Series.IN, now);
        assertEquals(TrafficHistory.SAMPLES, in[0].length);
        assertEquals(-(TrafficHistory.SAMPLES - 1), in[0][0], 0, "the oldest kept sample");
        assertEquals(0, in[0][in[0].length - 1], 0, "the newest is now");
        assertEquals(50, in[1][0], 0);
        assertEquals(2.0 * (TrafficHistory.SAMPLES + 49), h.series(ROBOT, TrafficHistory.Series.OUT, now)[1][
                TrafficHistory.SAMPLES - 1], 0);
    }

    @Test
    void secondsWithoutAnAnswerHaveNoRoundTripPoint() {
        TrafficHistory h = new TrafficHistory();
        h.add(1, snapshot(0, 0, 5));
        h.add(2, snapshot(0, 0, Double.NaN));
        h.add(3, snapshot(0, 0, 7));
        double[][] p99 = h.series(ROBOT, TrafficHistory.Series.ROUND_TRIP_P99, 3);
        assertArrayEquals(new double[] { -2, 0 }, p99[0]);
        assertArrayEquals(new double[] { 5, 7 }, p99[1]);
        h.remove(ROBOT);
        assertEquals(0, h.series(ROBOT, TrafficHistory.Series.IN, 3)[0].length);
    }

    @Test
    void errorsAreListedByConditionWithTheirTotal() {
        TrafficStatistics s = new TrafficStatistics(ROBOT, 0, 0, 0, 0, 0, 0, 0, 0, 5, Map.of(
                ControlMlCondition.TIMEOUT, 2L, ControlMlCondition.ACCESS_DENIED, 1L), 0, Double.NaN, Double.NaN, 0,
                0, Double.NaN);
        assertEquals("3: access-denied 1, timeout 2", TrafficTexts.errors(s));
        assertEquals("0", TrafficTexts.errors(snapshot(0, 0, 0)));
    }

    @Test
    void serverLineSaysTheArchivesFigures() {
        ServerFigures f = new ServerFigures(ROBOT, Duration.ofMinutes(15), 1, 9, 2, 7, 0, 9, 6,
                3, Map.of("set-not-permitted", 2L, "access-denied", 1L), 9, 3.4, 121.2, 1800, 0.4, 2718, Map.of(
                        "ejabberd@lab", 2718L));
        assertEquals("server's archive, last 15 min: 9 requests, 9 answers, 3 errors (access-denied 1, "
                + "set-not-permitted 2), answer p50 3.4 ms p99 121.2 ms, telemetry 2.00 Hz (last 0.4 s ago), "
                + "1 session(s) now", TrafficTexts.server(f));
    }
}
