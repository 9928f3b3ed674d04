package sabot.onboard.motion.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;

import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.AtomicReference;

import org.junit.jupiter.api.Test;

/** The control loop's real-time policy and timer slack: applied to the calling thread only, or refused with the reason. */
class RealtimeSchedulingTest {

    @Test
    void threadIsPutUnderFifoOrTheReasonIsGiven() throws InterruptedException {
        AtomicReference<String> refused = new AtomicReference<>();
        AtomicReference<String> policy = new AtomicReference<>();
        Thread t = new Thread(() -> {
            refused.set(RealtimeScheduling.applyToCurrentThread(10));
            policy.set(RealtimeScheduling.currentPolicy());
        }, "rt-test");
        t.start();
        t.join();
        if (refused.get() == null) {
            assertEquals("1", policy.get(), "SCHED_FIFO is policy 1");
        } else {
            assertNotNull(policy.get());
            assertEquals("0", policy.get(), "refused (" + refused.get() + "): the ordinary policy stays");
        }
        assertEquals("0", RealtimeScheduling.currentPolicy(), "other threads keep the ordinary policy");
    }

    @Test
    void timerSlackIsSetForTheCallingThreadOnly() throws InterruptedException {
        long before = RealtimeScheduling.currentTimerSlack();
        AtomicReference<String> refused = new AtomicReference<>();
        AtomicLong slack = new AtomicLong();
        Thread t = new Thread(() -> {
            refused.set(RealtimeScheduling.applyTimerSlackToCurrentThread(1_000));
            slack.set(RealtimeScheduling.currentTimerSlack());
        }, "slack-test");
        t.start();
        t.join();
        assertNull(refused.get(), "a thread may set its own timer slack");
        assertEquals(1_000, slack.get());
        assertEquals(before, RealtimeScheduling.currentTimerSlack(), "other threads keep theirs");
        assertThrows(IllegalArgumentException.class, () -> RealtimeScheduling.applyTimerSlackToCurrentThread(0));
    }

    @Test
    void priorityOutOfRangeIsRefused() {
        assertThrows(IllegalArgumentException.class, () -> RealtimeScheduling.applyToCurrentThread(0));
        assertThrows(IllegalArgumentException.class, () -> RealtimeScheduling.applyToCurrentThread(100));
    }
}
