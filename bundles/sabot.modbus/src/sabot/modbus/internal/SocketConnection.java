package sabot.modbus.internal;

import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.net.SocketTimeoutException;
import java.util.Set;

import com.ghgande.j2mod.modbus.io.AbstractModbusTransport;
import com.ghgande.j2mod.modbus.net.AbstractSerialConnection;

/**
 * A TCP socket seen as a serial port, so that j2mod's {@code ModbusRTUTransport} (RTU framing, CRC checked) runs over
 * RTU-over-TCP. j2mod's own RTU-over-TCP transport ({@code ModbusRTUTCPTransport}, through
 * {@code ModbusTCPTransport.readResponse}) reads the answer's CRC and discards it unchecked, so a corrupted answer
 * would be taken as good; {@link AbstractSerialConnection} is j2mod's extension point for another byte channel.
 * Reads end at the attempt's deadline ({@link #deadline(long)}).
 */
final class SocketConnection extends AbstractSerialConnection {

    private final String host;
    private final int port;
    private final int baud;
    private final int parity;
    private Socket socket;
    private InputStream in;
    private OutputStream out;
    private int timeoutMs;
    private volatile long deadlineNanos = Long.MAX_VALUE;

    SocketConnection(String host, int port, int baud, int parity, int timeoutMs) {
        this.host = host;
        this.port = port;
        this.baud = baud;
        this.parity = parity;
        this.timeoutMs = timeoutMs;
    }

    void deadline(long nanoTime) {
        deadlineNanos = nanoTime;
    }

    @Override
    public synchronized void open() throws IOException {
        Socket s = new Socket();
        try {
            s.setTcpNoDelay(true);
            s.connect(new InetSocketAddress(host, port), Math.max(1000, timeoutMs));
        } catch (IOException e) {
            s.close();
            throw new IOException("cannot connect to the RTU-over-TCP bus " + host + ":" + port + ": "
                    + e.getMessage(), e);
        }
        socket = s;
        in = s.getInputStream();
        out = s.getOutputStream();
    }

    @Override
    public AbstractModbusTransport getModbusTransport() {
        return null; // the Line owns its transport
    }

    @Override
    public int readBytes(byte[] buffer, int bytesToRead) {
        int got = 0;
        try {
            while (got < bytesToRead) {
                long left = Math.min(deadlineNanos - System.nanoTime(), timeoutMs * 1_000_000L);
                if (left <= 0) {
                    break;
                }
                socket.setSoTimeout((int) Math.max(1, (left + 999_999) / 1_000_000));
                int n = in.read(buffer, got, bytesToRead - got);
                if (n < 0) {
                    break; // the peer closed: no answer
                }
                got += n;
            }
        } catch (SocketTimeoutException e) {
            // a short count is how a timeout shows to the transport
        } catch (IOException e) {
            // the same for a broken connection: the attempt counts as unanswered
        }
        return got;
    }

    @Override
    public int writeBytes(byte[] buffer, int bytesToWrite) {
        try {
            out.write(buffer, 0, bytesToWrite);
            out.flush();
            return bytesToWrite;
        } catch (IOException e) {
            return 0;
        }
    }

    @Override
    public int bytesAvailable() {
        try {
            return in == null ? 0 : in.available();
        } catch (IOException e) {
            return 0;
        }
    }

    @Override
    public synchronized void close() {
        if (socket != null) {
            try {
                socket.close();
            } catch (IOException e) {
                // closing: nothing left to do with it
            }
        }
    }

    @Override
    public int getBaudRate() {
        return baud;
    }

    @Override
    public int getNumDataBits() {
        return 8;
    }

    @Override
    public int getNumStopBits() {
        return 1;
    }

    @Override
    public int getParity() {
        return parity;
    }

    @Override
    public String getPortName() {
        return host + ":" + port;
    }

    @Override
    public String getDescriptivePortName() {
        return "RTU over TCP " + host + ":" + port;
    }

    @Override
    public void setComPortTimeouts(int newTimeoutMode, int newReadTimeout, int newWriteTimeout) {
        timeoutMs = newReadTimeout;
    }

    @Override
    public synchronized boolean isOpen() {
        return socket != null && !socket.isClosed();
    }

    @Override
    public int getTimeout() {
        return timeoutMs;
    }

    @Override
    public void setTimeout(int timeout) {
        timeoutMs = timeout;
    }

    @Override
    public Set<String> getCommPorts() {
        return Set.of();
    }
}
