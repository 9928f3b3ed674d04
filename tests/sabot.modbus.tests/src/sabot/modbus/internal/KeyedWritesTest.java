package sabot.modbus.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Path;

import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

import sabot.modbus.BoardCounters;
import sabot.modbus.BusSettings;
import sabot.modbus.Motor;
import sabot.modbus.Parity;
import sabot.testsupport.robot.SimProcess;

/**
 * On a lossy bus (the simulator drops a fifth of the answers: the board applied the request, the master never heard
 * so) a retried position step must not move the commanded position twice. The SACT client keys every step with the
 * board's {@code command_sequence}, and the board answers a repeated key without applying it again: the commanded
 * position moves by exactly the steps sent. The control — the same steps written without a key — moves it by more.
 */
class KeyedWritesTest {

    private static final int STEPS = 60;

    @TempDir
    Path dir;

    @Test
    void aStepRetriedAfterALostAnswerIsAppliedOnce() throws Exception {
        try (SimProcess sim = SimProcess.start(dir, "--fault-drop", "0.2");
                Bus bus = Bus.open(BusSettings.serial(sim.pty()).withParity(Parity.NONE).withRetries(8))) {
            Bus.Counters raw = bus.new Counters("sact");
            ModbusMap.Field commanded = bus.map().field("sact", Motor.LEFT.mapFile(), "commanded_position");
            Span span = Span.of(commanded);

            long before = span.raw(commanded, bus.read(raw, span)[0]);
            for (int i = 0; i < STEPS; i++) {
                bus.sact().positionStep(Motor.LEFT, 1);
            }
            long keyed = span.raw(commanded, bus.read(raw, span)[0]) - before;
            BoardCounters c = bus.statistics().sact();
            assertTrue(c.timeouts() > 0, "no answer was lost: the test proves nothing (" + c + ")");
            assertEquals(STEPS, (int) keyed, "commanded position moved by " + keyed + " counts for " + STEPS
                    + " steps of 1 (" + c + ")");

            // the control: unkeyed, a retry after a lost answer applies the step again
            ModbusMap.Field step = bus.map().field("sact", Motor.LEFT.mapFile(), "position_step");
            long start = span.raw(commanded, bus.read(raw, span)[0]);
            for (int i = 0; i < STEPS; i++) {
                bus.write(raw, new Bus.Write(step.file(), step.record(), step.encode(1)));
            }
            long unkeyed = span.raw(commanded, bus.read(raw, span)[0]) - start;
            System.out.printf("[figure] %d steps of 1 count on a bus losing 20 %% of the answers: keyed %d counts, "
                    + "unkeyed %d counts%n", STEPS, keyed, unkeyed);
            assertTrue(unkeyed > STEPS, "without a key the retries were not applied twice: " + unkeyed);
        }
    }
}
