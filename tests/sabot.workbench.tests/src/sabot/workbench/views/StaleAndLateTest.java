package sabot.workbench.views;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Duration;
import java.time.Instant;

import org.junit.jupiter.api.Test;

import sabot.workbench.fleet.Availability;
import sabot.workbench.fleet.PoseLag;
import sabot.workbench.fleet.RobotState;

/**
 * When the Workspace and Fleet views grey a robot ({@link RobotState#isStale}): offline, no telemetry for
 * {@link RobotState#STALE_AFTER}, or poses that keep coming but late ({@link RobotState#isLate}, measured by
 * {@link PoseLag} without comparing the robot's clock with the workbench's). A robot publishing at 10 Hz, its clock
 * an hour off the workbench's, its transit 5 ms.
 */
class StaleAndLateTest {

    private static final Instant ROBOT_T0 = Instant.parse("2026-11-27T20:00:00Z");
    /** The workbench's monotonic clock at the robot's first pose: unrelated to the robot's clock. */
    private static final long WORKBENCH_T0 = 3_600_123_456_789L;
    private static final long PERIOD_NS = 100_000_000;
    private static final long TRANSIT_NS = 5_000_000;

    /** A robot whose poses the test delivers: stamp on its clock, receipt on the workbench's. */
    private static final class Robot {
        RobotState state = RobotState.unknown("sabot-01@sabot.local", "sabot-01").withPresence(Availability.FREE, "");
        Instant wallReceipt = Instant.parse("2026-11-27T19:00:00Z");

        /** Delivers a pose stamped {@code stampNs} after the robot's T0, received {@code receiptNs} after ours. */
        RobotState deliver(long stampNs, long receiptNs) {
            Instant at = wallReceipt.plusNanos(receiptNs);
            state = state.withPose(DrivenFleet.pose(1, 2, 0, ROBOT_T0.plusNanos(stampNs)), at, WORKBENCH_T0
                    + receiptNs);
            return state;
        }

        boolean staleAtReceipt() {
            return state.isStale(state.lastTelemetry());
        }
    }

    @Test
    void posesOnTimeAreLiveWhateverTheClocksOffset() {
        Robot r = new Robot();
        for (int k = 0; k < 100; k++) {
            r.deliver(k * PERIOD_NS, k * PERIOD_NS + TRANSIT_NS + (k % 7) * 1_000_000); // jitter 0..6 ms
            assertFalse(r.staleAtReceipt(), "pose " + k);
            assertFalse(r.state.isLate());
        }
        assertTrue(r.state.poseLag().lag().toMillis() <= 6, r.state.poseLag().toString());
        // no telemetry for longer than STALE_AFTER: stale by the receipt's age, not late
        Instant later = r.state.lastTelemetry().plus(RobotState.STALE_AFTER).plusMillis(1);
        assertTrue(r.state.isStale(later));
        assertFalse(r.state.isLate());
    }

    @Test
    void aBacklogGreysTheRobotWhilePosesKeepComingThenItIsLiveAgain() {
        Robot r = new Robot();
        for (int k = 0; k < 50; k++) {
            r.deliver(k * PERIOD_NS, k * PERIOD_NS + TRANSIT_NS);
        }
        // a 3 s stall on the way (the server stopped, or the workbench's ingest behind): the robot's 30 poses come
        // in one burst, 2 ms apart, after it
        long resume = 50 * PERIOD_NS + 3_000_000_000L;
        for (int k = 50; k < 80; k++) {
            long receipt = resume + (k - 50) * 2_000_000L;
            RobotState s = r.deliver(k * PERIOD_NS, receipt);
            // its delay (3 s, less 98 ms a pose of the burst) less the fastest delay (5 ms) and the drift allowance
            // of the time since the last pose on time (received at 4,905 ms)
            int j = k - 50;
            double lagMs = s.poseLag().lagNanos() / 1e6;
            assertEquals(2_995 - 98.0 * j - (8_000 + 2.0 * j - 4_905) * PoseLag.DRIFT_ALLOWANCE, lagMs, 0.001,
                    "pose " + k);
            // received just now, but late: grey while the lag exceeds STALE_AFTER (the burst's first 11 poses)
            assertEquals(j <= 10, r.staleAtReceipt(), "pose " + k + ", lag " + lagMs + " ms");
            assertEquals(r.staleAtReceipt(), s.isLate());
        }
        // caught up: on time again
        RobotState s = r.deliver(81 * PERIOD_NS, 81 * PERIOD_NS + TRANSIT_NS);
        assertFalse(r.staleAtReceipt(), s.poseLag().toString());
    }

    @Test
    void clocksThatDriftApartAreNotLag() {
        // the robot's clock runs 500 ppm slow for an hour: its poses' delay grows by 1.8 s
        Robot r = new Robot();
        for (long k = 0; k <= 36_000; k++) {
            long stamp = k * PERIOD_NS;
            r.deliver(stamp, stamp + stamp / 2000 + TRANSIT_NS);
            if (r.staleAtReceipt()) {
                throw new AssertionError("pose " + k + " late: " + r.state.poseLag());
            }
        }
        assertTrue(r.state.poseLag().lag().toMillis() < 1, r.state.poseLag().toString());
    }

    @Test
    void aLagThatStaysIsAbsorbedAtTheDriftAllowance() {
        Robot r = new Robot();
        r.deliver(0, TRANSIT_NS);
        // from now on every pose is 3 s late: still grey after 900 s, live again within 1,100 s (3 s - 2 s at 1 ms/s)
        long lateNs = 3_000_000_000L;
        for (long k = 1; k <= 11_000; k++) {
            r.deliver(k * PERIOD_NS, k * PERIOD_NS + TRANSIT_NS + lateNs);
            if (k == 9_000) {
                assertTrue(r.state.isLate(), r.state.poseLag().toString());
            }
        }
        assertFalse(r.state.isLate(), r.state.poseLag().toString());
        assertEquals(1_900, r.state.poseLag().lag().toMillis(), 5, "3 s less 1 ms a second for 1,100 s");
    }

    @Test
    void aRobotClockSteppedBackStartsAnewSteppedForwardLowersTheDelays() {
        Robot r = new Robot();
        for (int k = 0; k < 10; k++) {
            r.deliver(k * PERIOD_NS, k * PERIOD_NS + TRANSIT_NS);
        }
        // NTP steps the robot's clock 10 s back: its stamps go backwards, which no backlog does
        long back = 10_000_000_000L;
        for (int k = 10; k < 20; k++) {
            r.deliver(k * PERIOD_NS - back, k * PERIOD_NS + TRANSIT_NS);
            assertFalse(r.staleAtReceipt(), "pose " + k + ": " + r.state.poseLag());
        }
        // and 10 s forward: the delays fall, the least with them
        for (int k = 20; k < 30; k++) {
            r.deliver(k * PERIOD_NS, k * PERIOD_NS + TRANSIT_NS);
            assertFalse(r.staleAtReceipt(), "pose " + k + ": " + r.state.poseLag());
        }
    }

    @Test
    void aRobotThatComesOnlineAgainStartsItsLagAnew() {
        Robot r = new Robot();
        r.deliver(0, TRANSIT_NS);
        r.deliver(PERIOD_NS, PERIOD_NS + TRANSIT_NS + 2_500_000_000L);
        assertTrue(r.state.isLate());
        assertTrue(r.state.withPresence(Availability.BUSY, "mission").isLate(), "a presence change keeps it");
        RobotState offline = r.state.withPresence(Availability.OFFLINE, "");
        assertTrue(offline.isStale(offline.lastTelemetry()));
        assertFalse(offline.isLate(), "offline: stale, not late (the map labels it so)");
        RobotState back = offline.withPresence(Availability.FREE, "");
        assertNull(back.poseLag(), "it may have restarted with another clock");
        assertFalse(back.isLate());
        assertFalse(back.isStale(back.lastTelemetry()));
        // the backlog's last poses arrive after the robot went offline: still not late, and forgotten when it is back
        r.state = offline;
        r.deliver(2 * PERIOD_NS, 2 * PERIOD_NS + TRANSIT_NS);
        r.deliver(3 * PERIOD_NS, 3 * PERIOD_NS + TRANSIT_NS + 5_000_000_000L);
        assertTrue(r.state.poseLag().lag().compareTo(RobotState.STALE_AFTER) > 0, "these poses lag: " + r.state
                .poseLag());
        assertFalse(r.state.isLate(), "offline: stale, not late, whatever arrives: " + r.state.poseLag());
        assertNull(r.state.withPresence(Availability.FREE, "").poseLag(), "a lag measured while offline is dropped");
    }

    @Test
    void theFleetViewSaysHowLate() {
        Robot r = new Robot();
        r.deliver(0, TRANSIT_NS);
        r.deliver(PERIOD_NS, PERIOD_NS + TRANSIT_NS + 2_400_000_000L);
        assertEquals("0.3 s, 2.4 s late", FleetView.texts(r.state, r.state.lastTelemetry().plusMillis(300)).get(4));
        r.deliver(30 * PERIOD_NS, 30 * PERIOD_NS + TRANSIT_NS);
        assertEquals("0.3 s", FleetView.texts(r.state, r.state.lastTelemetry().plusMillis(300)).get(4));
    }

    @Test
    void aNegativeLagIsRefused() {
        assertThrows(IllegalArgumentException.class, () -> new PoseLag(0, -1, 0, ROBOT_T0));
        assertEquals(Duration.ZERO, PoseLag.first(ROBOT_T0, 42).lag());
    }
}
