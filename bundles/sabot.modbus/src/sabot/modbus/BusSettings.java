package sabot.modbus;

import java.time.Duration;

import sabot.modbus.internal.ModbusMap;

/**
 * How to reach one RS-485 bus: a serial port, or a TCP host and port carrying Modbus RTU frames (with CRC, not MBAP).
 * Build one with {@link #serial(String)} or {@link #tcp(String, int)} and the {@code with...} methods; every value is
 * checked when the record is made.
 *
 * @param serialPort       path of the serial device (e.g. {@code /dev/ttyUSB0}, a simulator's pty); {@code null} for
 *                         TCP
 * @param tcpHost          host of an RTU-over-TCP peer; {@code null} for a serial port
 * @param tcpPort          TCP port, 1–65535 (0 for a serial port)
 * @param baud             line speed in bit/s (default from the register map, 115200); also used on TCP to compute
 *                         wire times
 * @param parity           character parity (default {@link Parity#EVEN}; {@link Parity#NONE} for a pty)
 * @param responseTimeout  how long one attempt waits for an answer, 1 ms–10 s (default 50 ms)
 * @param retries          attempts after the first when an answer is lost or corrupt, 0–10 (default 1)
 * @param interFrameDelay  silence kept between the end of an answer and the next request, 0–1 s (default t3.5 of
 *                         the register map, 1.75 ms)
 * @param faultAfter       a board with no good answer for this long is faulted, 1 ms–1 min (default 200 ms)
 */
public record BusSettings(String serialPort, String tcpHost, int tcpPort, int baud, Parity parity,
        Duration responseTimeout, int retries, Duration interFrameDelay, Duration faultAfter) {

    /** Default response timeout: 50 ms. */
    public static final Duration DEFAULT_RESPONSE_TIMEOUT = Duration.ofMillis(50);
    /** Default retries: 1. */
    public static final int DEFAULT_RETRIES = 1;
    /** Default fault time: 200 ms. */
    public static final Duration DEFAULT_FAULT_AFTER = Duration.ofMillis(200);

    /** Checks every field. @throws IllegalArgumentException naming the field, its value and what is allowed */
    public BusSettings {
        if (serialPort == null && tcpHost == null) {
            throw new IllegalArgumentException("BusSettings: give a serial port or a TCP host");
        }
        if (serialPort != null && tcpHost != null) {
            throw new IllegalArgumentException("BusSettings: give a serial port or a TCP host, not both (serialPort "
                    + serialPort + ", tcpHost " + tcpHost + ")");
        }
        if (serialPort != null && serialPort.isBlank()) {
            throw new IllegalArgumentException("BusSettings: serialPort is blank");
        }
        if (serialPort != null && tcpPort != 0) {
            throw new IllegalArgumentException("BusSettings: tcpPort " + tcpPort + " given with a serial port");
        }
        if (tcpHost != null && tcpHost.isBlank()) {
            throw new IllegalArgumentException("BusSettings: tcpHost is blank");
        }
        if (tcpHost != null && (tcpPort < 1 || tcpPort > 65535)) {
            throw new IllegalArgumentException("BusSettings: tcpPort must be 1-65535, got " + tcpPort);
        }
        if (baud < 300 || baud > 4_000_000) {
            throw new IllegalArgumentException("BusSettings: baud must be 300-4000000 bit/s, got " + baud);
        }
        if (parity == null) {
            throw new IllegalArgumentException("BusSettings: parity is null");
        }
        check("responseTimeout", responseTimeout, Duration.ofMillis(1), Duration.ofSeconds(10));
        if (retries < 0 || retries > 10) {
            throw new IllegalArgumentException("BusSettings: retries must be 0-10, got " + retries);
        }
        check("interFrameDelay", interFrameDelay, Duration.ZERO, Duration.ofSeconds(1));
        check("faultAfter", faultAfter, Duration.ofMillis(1), Duration.ofMinutes(1));
    }

    private static void check(String name, Duration d, Duration min, Duration max) {
        if (d == null) {
            throw new IllegalArgumentException("BusSettings: " + name + " is null");
        }
        if (d.compareTo(min) < 0 || d.compareTo(max) > 0) {
            throw new IllegalArgumentException("BusSettings: " + name + " must be " + text(min) + "-" + text(max)
                    + ", got " + text(d));
        }
    }

    private static String text(Duration d) {
        long ns = d.toNanos();
        return ns % 1_000_000 == 0 ? ns / 1_000_000 + " ms" : ns / 1000.0 + " µs";
    }

    /**
     * @param port path of the serial device
     * @return settings for that port with the defaults (baud and parity of the register map, 50 ms, 1 retry,
     *         t3.5, 200 ms)
     */
    public static BusSettings serial(String port) {
        ModbusMap map = ModbusMap.standard();
        return new BusSettings(port, null, 0, map.baud(), mapParity(map), DEFAULT_RESPONSE_TIMEOUT, DEFAULT_RETRIES,
                map.t35(), DEFAULT_FAULT_AFTER);
    }

    /**
     * @param host RTU-over-TCP peer
     * @param port its TCP port
     * @return settings for that peer with the defaults
     */
    public static BusSettings tcp(String host, int port) {
        ModbusMap map = ModbusMap.standard();
        return new BusSettings(null, host, port, map.baud(), mapParity(map), DEFAULT_RESPONSE_TIMEOUT,
                DEFAULT_RETRIES, map.t35(), DEFAULT_FAULT_AFTER);
    }

    private static Parity mapParity(ModbusMap map) {
        return switch (map.parity()) {
            case "N" -> Parity.NONE;
            case "O" -> Parity.ODD;
            default -> Parity.EVEN;
        };
    }

    /** @return whether this bus is RTU-over-TCP */
    public boolean isTcp() {
        return tcpHost != null;
    }

    /** @return a copy with another baud rate (bit/s) */
    public BusSettings withBaud(int newBaud) {
        return new BusSettings(serialPort, tcpHost, tcpPort, newBaud, parity, responseTimeout, retries,
                interFrameDelay, faultAfter);
    }

    /** @return a copy with another parity */
    public BusSettings withParity(Parity newParity) {
        return new BusSettings(serialPort, tcpHost, tcpPort, baud, newParity, responseTimeout, retries,
                interFrameDelay, faultAfter);
    }

    /** @return a copy with another response timeout */
    public BusSettings withResponseTimeout(Duration timeout) {
        return new BusSettings(serialPort, tcpHost, tcpPort, baud, parity, timeout, retries, interFrameDelay,
                faultAfter);
    }

    /** @return a copy with another number of retries */
    public BusSettings withRetries(int newRetries) {
        return new BusSettings(serialPort, tcpHost, tcpPort, baud, parity, responseTimeout, newRetries,
                interFrameDelay, faultAfter);
    }

    /** @return a copy with another inter-frame delay */
    public BusSettings withInterFrameDelay(Duration delay) {
        return new BusSettings(serialPort, tcpHost, tcpPort, baud, parity, responseTimeout, retries, delay,
                faultAfter);
    }

    /** @return a copy with another fault time */
    public BusSettings withFaultAfter(Duration after) {
        return new BusSettings(serialPort, tcpHost, tcpPort, baud, parity, responseTimeout, retries,
                interFrameDelay, after);
    }

    /** @return the longest one transaction can take before it fails: response timeout × (retries + 1) */
    public Duration transactionBound() {
        return responseTimeout.multipliedBy(retries + 1L);
    }

    /** @return the serial port or host:port */
    public String where() {
        return isTcp() ? tcpHost + ":" + tcpPort : serialPort;
    }
}
