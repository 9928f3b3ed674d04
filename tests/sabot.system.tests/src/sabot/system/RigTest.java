package sabot.system;

import java.util.concurrent.TimeUnit;
import java.util.function.Predicate;

import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;

import sabot.testsupport.xmpp.PrivateXmppServer;
import sabot.testsupport.robot.SimProcess;

/**
 * What the system tests share: a private Prosody per test (started in ~0.1-0.2 s; accounts do not leak between
 * tests), the lab's free start poses, and waits on the simulator's ground truth.
 */
abstract class RigTest {

    /** Left of the lab's partition (x 3.0–3.6 m, y 2.2–6.0 m), facing +x. */
    static final double[] WEST_OF_PARTITION = { 1.5, 4.0, 0.0 };
    /** The lab's lower corridor (y 0.15–2.2 m), west end, facing +x: 9 m free ahead. */
    static final double[] CORRIDOR_WEST = { 1.5, 1.0, 0.0 };
    /** The lower corridor past the partition, facing +x: 4 m free ahead. */
    static final double[] CORRIDOR_MIDDLE = { 4.5, 1.0, 0.0 };
    /** The robot's linear acceleration limit, m/s² (docs/sabot-robot.properties). */
    static final double A_MAX = 0.5;
    /** The joystick's rate, Hz, as the workbench's joystick sends it. */
    static final int JOYSTICK_HZ = 10;

    protected final PrivateXmppServer xmpp = newServer();

    /** @return the test's server, not started: a private Prosody; a test of a cluster overrides it */
    protected PrivateXmppServer newServer() {
        return PrivateXmppServer.prosody();
    }

    @BeforeEach
    void startServer() throws Exception {
        xmpp.start();
    }

    @AfterEach
    void stopServer() {
        xmpp.close();
    }

    /**
     * Reads the simulator's truth until {@code condition} holds. The robot is an external process with no event to
     * wait on, so this polls the simulator every 20 ms, up to {@code withinSeconds} of the simulator's own clock.
     */
    static SimProcess.Truth awaitTruth(SimProcess sim, Predicate<SimProcess.Truth> condition, double withinSeconds,
            String what) throws Exception {
        double deadline = sim.truth().t() + withinSeconds;
        while (true) {
            SimProcess.Truth t = sim.truth();
            if (condition.test(t)) {
                return t;
            }
            if (t.t() > deadline) {
                throw new AssertionError("robot not " + what + " within " + withinSeconds + " s: " + t);
            }
            TimeUnit.MILLISECONDS.sleep(20);
        }
    }

    /** Waits until the robot stands still: |v| < 5 mm/s and |ω| < 0.01 rad/s. */
    static SimProcess.Truth awaitStandstill(SimProcess sim, double withinSeconds) throws Exception {
        return awaitTruth(sim, t -> Math.abs(t.v()) < 0.005 && Math.abs(t.omega()) < 0.01, withinSeconds,
                "standing still");
    }

    /** Waits until the robot drives at {@code speed} m/s or faster. */
    static SimProcess.Truth awaitSpeed(SimProcess sim, double speed, double withinSeconds) throws Exception {
        return awaitTruth(sim, t -> t.v() >= speed, withinSeconds, "driving at " + speed + " m/s");
    }

    /** Waits for {@code seconds} of the simulator's clock and returns the truth then. */
    static SimProcess.Truth awaitSimTime(SimProcess sim, double seconds) throws Exception {
        double until = sim.truth().t() + seconds;
        return awaitTruth(sim, t -> t.t() >= until, seconds + 5, "(the simulator's clock stopped)");
    }
}
