package sabot.onboard.motion.loop;

import java.time.Instant;

/**
 * The control loop's time, from outside: the robot's is the JVM's monotonic clock and the wall clock; a test's or the
 * motion simulation's advances when it is told to, so the real loop can be driven period by period in milliseconds.
 */
public interface LoopClock {

    /** The JVM's clocks: {@link System#nanoTime()} and {@link Instant#now()}. */
    LoopClock SYSTEM = new LoopClock() {
        @Override
        public long nanoTime() {
            return System.nanoTime();
        }

        @Override
        public Instant now() {
            return Instant.now();
        }
    };

    /** @return monotonic time, ns (any origin; only differences count) */
    long nanoTime();

    /** @return wall-clock time: stamps of reports, and the latency of a joystick twist sent at a wall-clock time */
    Instant now();
}
