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
 * (FIONREAD) every {@value #POLL_NANOS} ns, then reads only what is there.
 */
final class ObservedConnection extends AbstractSerialConnection {

    /** How often a serial read checks for its bytes: below one character time at 115200 baud (95 µs). */
    static final long POLL_NANOS = 50_000;

    private final AbstractSerialConnection inner;
    private final boolean pollSerial;
    private long deadlineNanos = Long.MAX_VALUE;
    private boolean unanswered;

    ObservedConnection(AbstractSerialConnection inner) {
        this.inner = inner;
        this.pollSerial = !(inner instanceof SocketConnection);
    }

    /** Starts an attempt that must end by {@code nanoTime}. */
    void startAttempt(long nanoTime) {
        deadlineNanos = nanoTime;
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
            while ((available = inner.bytesAvailable()) < bytesToRead && System.nanoTime() < deadlineNanos) {
                // waits for the slave's bytes (a condition on the port), bounded by the attempt's deadline
                LockSupport.parkNanos(POLL_NANOS);
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
