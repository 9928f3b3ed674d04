package sabot.modbus.internal;

import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.concurrent.locks.LockSupport;

import com.ghgande.j2mod.modbus.Modbus;
import com.ghgande.j2mod.modbus.ModbusIOException;
import com.ghgande.j2mod.modbus.io.ModbusRTUTransport;
import com.ghgande.j2mod.modbus.msg.ModbusRequest;
import com.ghgande.j2mod.modbus.msg.ModbusResponse;
import com.ghgande.j2mod.modbus.net.AbstractSerialConnection;
import com.ghgande.j2mod.modbus.net.SerialConnection;
import com.ghgande.j2mod.modbus.util.SerialParameters;

import sabot.modbus.BusSettings;
import sabot.modbus.BusTiming;
import sabot.modbus.Parity;

/**
 * The byte channel of one bus and j2mod's RTU transport on it: one attempt of one request at a time, the inter-frame
 * silence kept before each. Retries, counters and the meaning of answers belong to {@link Bus}; j2mod's own
 * {@code ModbusSerialTransaction} is not used because its retries sleep a random back-off and it cannot tell a
 * timeout from a CRC error.
 */
final class Line implements AutoCloseable {

    /** What one attempt came to. */
    sealed interface Attempt {
        /** a frame that passed the CRC check */
        record Answer(ModbusResponse response) implements Attempt {
        }

        /** nothing, or not all of a frame, within the timeout */
        record Unanswered(String detail) implements Attempt {
        }

        /** a whole frame whose CRC or format is wrong */
        record Corrupt(String detail) implements Attempt {
        }
    }

    private final BusSettings settings;
    private final AbstractSerialConnection channel;
    private final ObservedConnection observed;
    private final ModbusRTUTransport transport;
    private final long interFrameNanos;
    private final long timeoutNanos;
    private long lastFrameEnd = System.nanoTime();

    private Line(BusSettings settings, AbstractSerialConnection channel) throws IOException {
        this.settings = settings;
        this.channel = channel;
        BusTiming timing = BusTiming.of(settings);
        this.observed = new ObservedConnection(channel, timing.characterTime().toNanos(), timing.t35().toNanos());
        this.timeoutNanos = settings.responseTimeout().toNanos();
        this.interFrameNanos = settings.interFrameDelay().toNanos();
        int timeoutMs = (int) Math.max(1, settings.responseTimeout().toMillis());
        channel.setTimeout(timeoutMs);
        channel.open();
        transport = new ModbusRTUTransport();
        transport.setTimeout(timeoutMs);
        transport.setCommPort(observed);
    }

    /** Opens the serial port or connects the socket of {@code settings}. */
    static Line open(BusSettings settings) throws IOException {
        int parity = switch (settings.parity()) {
            case NONE -> AbstractSerialConnection.NO_PARITY;
            case EVEN -> AbstractSerialConnection.EVEN_PARITY;
            case ODD -> AbstractSerialConnection.ODD_PARITY;
        };
        if (settings.isTcp()) {
            return new Line(settings, new SocketConnection(settings.tcpHost(), settings.tcpPort(), settings.baud(),
                    parity, (int) Math.max(1, settings.responseTimeout().toMillis())));
        }
        String port = settings.serialPort();
        if (!Files.exists(Path.of(port))) {
            throw new IOException("serial port " + port + " does not exist");
        }
        SerialParameters p = new SerialParameters();
        p.setPortName(port);
        p.setBaudRate(settings.baud());
        p.setDatabits(8);
        // Modbus RTU keeps 11 bits per character: without parity, two stop bits
        p.setStopbits(settings.parity() == Parity.NONE ? 2 : 1);
        p.setParity(parity);
        p.setEncoding(Modbus.SERIAL_ENCODING_RTU);
        p.setEcho(false);
        try {
            return new Line(settings, new SerialConnection(p));
        } catch (IOException | RuntimeException e) {
            // jSerialComm throws SerialPortInvalidPortException (unchecked) for a path it cannot use
            throw new IOException("cannot open serial port " + port + ": " + e.getMessage(), e);
        }
    }

    /**
     * Sends {@code request} once and reads the answer: keeps the inter-frame silence first, then gives the answer
     * {@code responseTimeout} to arrive.
     *
     * @param answerBytes the answer's length when it is not an exception answer: the reads wait for the time the line
     *                    needs to bring it before they look for it
     */
    Attempt attempt(ModbusRequest request, int answerBytes) {
        long quietUntil = lastFrameEnd + interFrameNanos;
        for (long wait = quietUntil - System.nanoTime(); wait > 0; wait = quietUntil - System.nanoTime()) {
            // the line's protocol silence (t3.5), not a synchronisation: the slave needs it to see the frame end
            LockSupport.parkNanos(wait);
        }
        observed.startAttempt(System.nanoTime() + timeoutNanos, answerBytes);
        try {
            transport.writeRequest(request);
            ModbusResponse response = transport.readResponse();
            return new Attempt.Answer(response);
        } catch (ModbusIOException e) {
            if (!channel.isOpen()) {
                return new Attempt.Unanswered("the port " + settings.where() + " is closed: " + e.getMessage());
            }
            return observed.unanswered() ? new Attempt.Unanswered(e.getMessage())
                    : new Attempt.Corrupt(e.getMessage());
        } finally {
            lastFrameEnd = System.nanoTime();
        }
    }

    /** @return where the line goes, for messages */
    String where() {
        return settings.where();
    }

    @Override
    public void close() {
        channel.close();
    }
}
