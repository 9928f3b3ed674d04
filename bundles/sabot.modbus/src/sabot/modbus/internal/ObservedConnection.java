package sabot.modbus.internal;

import java.io.IOException;
import java.util.Set;
import java.util.concurrent.locks.LockSupport;

import com.ghgande.j2mod.modbus.io.AbstractModbusTransport;
import com.ghgande.j2mod.modbus.net.AbstractSerialConnection;

/**
 * Sits between j2mod's RTU transport and the byte channel (j2mod's jSerialComm {@code SerialConnection}, or
 * {@link SocketConnection}) to tell a timeout from a corrupt answer: j2mod reports both as a
 * {@code ModbusIOException} that differs only in its message. A read that returns fewer bytes than asked, or any
 * read after the attempt's deadline, is a timeout; a failed write counts as no answer.
 * <p>
 * It also keeps the response timeout exact on a serial port. jSerialComm implements a blocking read with a timeout
 * through termios {@code VTIME}, which counts in tenths of a second ({@code VTIME = readTimeout / 100}, rounded up to
 * one tick), so a 50 ms timeout lasts 100 ms and the bound timeout × attempts would not hold. Before each read this
 * class waits until the bytes asked for are there or the deadline has come, checking {@code bytesAvailable()}
 * (FIONREAD), then reads only what is there.
 * <p>
 * The checks start when the line can have brought the answer, not at once: the request must cross the line, the slave
 * must see the inter-frame silence after it (t3.5) before it answers, and the answer's bytes take one character time
 * each. Until then the thread sleeps; after, it checks every {@value #POLL_NANOS} ns. (Checking every 50 µs from the
 * write on cost about 28 wake-ups per transaction on the robot's bus, a few per cent of a core.) An exception answer,
 * shorter than the one expected, is read that much later, within the timeout.
 */
final class ObservedConnection extends AbstractSerialConnection {

    /** How often a serial read checks for its bytes: below one character time at 115200 baud (95 µs). */
    static final long POLL_NANOS = 50_000;

    private final AbstractSerialConnection inner;
    private final boolean pollSerial;
    private final long characterNanos;
    private final long silenceNanos;
    private long deadlineNanos = Long.MAX_VALUE;
    /** Bytes of the answer expected in this attempt. */
    private int answerBytes;
    /** The earliest time the whole answer can be there: the request and the answer on the line, and t3.5. */
    private long answerNanos = Long.MIN_VALUE;
    private boolean unanswered;

    /**
     * @param characterNanos one character's time on the line (11 bits at the baud rate)
     * @param silenceNanos   the inter-frame silence (t3.5) a slave waits for before it answers
     */
    ObservedConnection(AbstractSerialConnection inner, long characterNanos, long silenceNanos) {
        this.inner = inner;
        this.pollSerial = !(inner instanceof SocketConnection);
        this.characterNanos = characterNanos;
        this.silenceNanos = silenceNanos;
    }

    /** Starts an attempt that must end by {@code nanoTime}, whose answer is {@code answerBytes} long. */
    void startAttempt(long nanoTime, int answerBytes) {
        deadlineNanos = nanoTime;
        this.answerBytes = answerBytes;
        answerNanos = Long.MIN_VALUE;
        unanswered = false;
        if (inner instanceof SocketConnection s) {
            s.deadline(nanoTime);
        }
    }

    /** @return whether the attempt ran out of time or lost its channel */
    boolean unanswered() {
        return unanswered;
    }

    @Override
    public int readBytes(byte[] buffer, int bytesToRead) {
        if (System.nanoTime() >= deadlineNanos) {
            unanswered = true;
            return 0;
        }
        int ask = bytesToRead;
        if (pollSerial) {
            int available;
            long now;
            while ((available = inner.bytesAvailable()) < bytesToRead && (now = System.nanoTime()) < deadlineNanos) {
                // waits for the slave's bytes (a condition on the port), bounded by the attempt's deadline, no sooner
                // than the line can bring them
                long due = Math.max(answerNanos, now + POLL_NANOS);
                LockSupport.parkNanos(Math.min(deadlineNanos, due) - now);
            }
            available = inner.bytesAvailable();
            if (available <= 0) {
                unanswered = true;
                return 0;
            }
            ask = Math.min(bytesToRead, available);
        }
        int got = inner.readBytes(buffer, ask);
        if (got < bytesToRead) {
            unanswered = true;
        }
        return Math.max(got, 0);
    }

    @Override
    public int writeBytes(byte[] buffer, int bytesToWrite) {
        answerNanos = System.nanoTime() + (long) (bytesToWrite + answerBytes) * characterNanos + silenceNanos;
        int n = inner.writeBytes(buffer, bytesToWrite);
        if (n != bytesToWrite) {
            unanswered = true;
        }
        return n;
    }

    @Override
    public int bytesAvailable() {
        return Math.max(0, inner.bytesAvailable());
    }

    @Override
    public void open() throws IOException {
        inner.open();
    }

    @Override
    public AbstractModbusTransport getModbusTransport() {
        return null;
    }

    @Override
    public void close() {
        inner.close();
    }

    @Override
    public int getBaudRate() {
        return inner.getBaudRate();
    }

    @Override
    public int getNumDataBits() {
        return inner.getNumDataBits();
    }

    @Override
    public int getNumStopBits() {
        return inner.getNumStopBits();
    }

    @Override
    public int getParity() {
        return inner.getParity();
    }

    @Override
    public String getPortName() {
        return inner.getPortName();
    }

    @Override
    public String getDescriptivePortName() {
        return inner.getDescriptivePortName();
    }

    @Override
    public void setComPortTimeouts(int newTimeoutMode, int newReadTimeout, int newWriteTimeout) {
        inner.setComPortTimeouts(newTimeoutMode, newReadTimeout, newWriteTimeout);
    }

    @Override
    public boolean isOpen() {
        return inner.isOpen();
    }

    @Override
    public int getTimeout() {
        return inner.getTimeout();
    }

    @Override
    public void setTimeout(int timeout) {
        inner.setTimeout(timeout);
    }

    @Override
    public Set<String> getCommPorts() {
        return inner.getCommPorts();
    }
}
