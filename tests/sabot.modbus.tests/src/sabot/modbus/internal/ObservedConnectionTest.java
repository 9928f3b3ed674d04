package sabot.modbus.internal;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.ArrayList;
import java.util.List;
import java.util.Set;

import org.junit.jupiter.api.Test;

import com.ghgande.j2mod.modbus.io.AbstractModbusTransport;
import com.ghgande.j2mod.modbus.net.AbstractSerialConnection;

/**
 * How the master waits for an answer on a serial port: it looks for the bytes only once the line can have brought
 * them (the request, the slave's t3.5, the answer, at 11 bits a character), and still reads a timeout at the
 * attempt's deadline. On a port that counts the checks, the way sabot-sim's pty delivers a frame: whole, once due.
 */
class ObservedConnectionTest {

    /** 11 bits at 115200 baud, ns. */
    private static final long CHARACTER = 95_486;
    private static final long T35 = 1_750_000;
    private static final int REQUEST = 8;
    private static final int ANSWER = 25;

    /** A port whose answer is all there from one moment on; it records when its bytes were looked for. */
    private static final class ScriptedPort extends AbstractSerialConnection {
        final byte[] answer;
        volatile long arrival = Long.MAX_VALUE;
        final List<Long> checks = new ArrayList<>();
        int taken;

        ScriptedPort(byte[] answer) {
            this.answer = answer;
        }

        @Override
        public int bytesAvailable() {
            long now = System.nanoTime();
            checks.add(now);
            return now >= arrival ? answer.length - taken : 0;
        }

        @Override
        public int readBytes(byte[] buffer, int bytesToRead) {
            int n = Math.min(bytesToRead, System.nanoTime() >= arrival ? answer.length - taken : 0);
            System.arraycopy(answer, taken, buffer, 0, n);
            taken += n;
            return n;
        }

        @Override
        public int writeBytes(byte[] buffer, int bytesToWrite) {
            return bytesToWrite;
        }

        @Override
        public void open() {
        }

        @Override
        public AbstractModbusTransport getModbusTransport() {
            return null;
        }

        @Override
        public void close() {
        }

        @Override
        public int getBaudRate() {
            return 115200;
        }

        @Override
        public int getNumDataBits() {
            return 8;
        }

        @Override
        public int getNumStopBits() {
            return 2;
        }

        @Override
        public int getParity() {
            return NO_PARITY;
        }

        @Override
        public String getPortName() {
            return "scripted";
        }

        @Override
        public String getDescriptivePortName() {
            return "scripted";
        }

        @Override
        public void setComPortTimeouts(int newTimeoutMode, int newReadTimeout, int newWriteTimeout) {
        }

        @Override
        public boolean isOpen() {
            return true;
        }

        @Override
        public int getTimeout() {
            return 50;
        }

        @Override
        public void setTimeout(int timeout) {
        }

        @Override
        public Set<String> getCommPorts() {
            return Set.of();
        }
    }

    private static byte[] answer() {
        byte[] a = new byte[ANSWER];
        for (int i = 0; i < a.length; i++) {
            a[i] = (byte) (i * 7 + 1);
        }
        return a;
    }

    @Test
    void theAnswerIsLookedForOnlyOnceTheLineCanHaveBroughtIt() {
        ScriptedPort port = new ScriptedPort(answer());
        ObservedConnection line = new ObservedConnection(port, CHARACTER, T35);
        line.startAttempt(System.nanoTime() + 50_000_000L, ANSWER);
        long written = System.nanoTime();
        long earliest = written + (REQUEST + ANSWER) * CHARACTER + T35;
        port.arrival = earliest;
        line.writeBytes(new byte[REQUEST], REQUEST);

        // j2mod reads an answer in pieces: the slave's address, the function code, then the rest
        byte[] got = new byte[ANSWER];
        assertEquals(1, line.readBytes(got, 1));
        assertEquals(1, line.readBytes(new byte[1], 1));
        assertEquals(ANSWER - 2, line.readBytes(new byte[ANSWER - 2], ANSWER - 2));
        assertEquals(answer()[0], got[0]);
        assertFalse(line.unanswered());

        long early = port.checks.stream().filter(t -> t < earliest).count();
        // the first look, and a spurious wake-up at most; a 50 µs poll from the write on would look about 100 times
        assertTrue(early <= 3, early + " looks before the answer could be there (" + port.checks.size() + " in all)");
        long firstLate = port.checks.stream().filter(t -> t >= earliest).findFirst().orElseThrow();
        assertTrue(firstLate - earliest < 20_000_000L, "looked " + (firstLate - earliest) / 1000 + " µs after it came");
    }

    @Test
    void anAnswerThatNeverComesIsATimeoutAtTheDeadline() {
        ScriptedPort port = new ScriptedPort(answer());
        ObservedConnection line = new ObservedConnection(port, CHARACTER, T35);
        long start = System.nanoTime();
        line.startAttempt(start + 20_000_000L, ANSWER);
        line.writeBytes(new byte[REQUEST], REQUEST);
        assertEquals(0, line.readBytes(new byte[1], 1));
        long waited = System.nanoTime() - start;
        assertTrue(line.unanswered());
        assertTrue(waited >= 20_000_000L, "gave up after " + waited / 1000 + " µs, before the deadline");
        assertEquals(0, line.readBytes(new byte[1], 1), "a read after the deadline is a timeout at once");
    }

    @Test
    void aShorterAnswerIsReadWithinTheTimeout() {
        // an exception answer (5 bytes) comes earlier than the answer expected: it is read late, but read
        byte[] exception = { 1, (byte) 0x94, 2, 0x13, 0x2c };
        ScriptedPort port = new ScriptedPort(exception);
        ObservedConnection line = new ObservedConnection(port, CHARACTER, T35);
        line.startAttempt(System.nanoTime() + 50_000_000L, ANSWER);
        port.arrival = System.nanoTime() + (REQUEST + exception.length) * CHARACTER + T35;
        line.writeBytes(new byte[REQUEST], REQUEST);
        byte[] got = new byte[exception.length];
        assertEquals(1, line.readBytes(got, 1));
        byte[] rest = new byte[exception.length - 1];
        assertEquals(rest.length, line.readBytes(rest, rest.length));
        System.arraycopy(rest, 0, got, 1, rest.length);
        assertArrayEquals(exception, got);
        assertFalse(line.unanswered());
    }
}
