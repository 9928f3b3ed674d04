package sabot.modbus;

import java.time.Duration;

import sabot.modbus.internal.ModbusMap;

/**
 * The time a transaction takes on the wire: (request bytes + answer bytes) × bits per character / baud + t3.5 (the
 * silence that ends the request before the slave may answer). A Modbus RTU character is always 11 bits (start, 8
 * data, parity or a second stop bit, stop), as in the register map's 8E1. This is the physical limit a control loop
 * budgets with and the benchmark compares against.
 */
public final class BusTiming {

    /** Frame overhead: slave address, function code, byte count, CRC (2). */
    private static final int FRAME_OVERHEAD = 5;
    /** A file-record read sub-request: reference type, file (2), record (2), length (2). */
    private static final int READ_SUB_REQUEST = 7;
    /** A file-record read sub-answer's header: length, reference type. */
    private static final int READ_SUB_ANSWER = 2;

    private final int baud;
    private final int bitsPerCharacter;
    private final Duration t35;

    /**
     * @param baud             line speed, bit/s
     * @param bitsPerCharacter bits on the line per byte (11 for Modbus RTU)
     * @param t35              the inter-frame silence
     */
    public BusTiming(int baud, int bitsPerCharacter, Duration t35) {
        if (baud <= 0 || bitsPerCharacter <= 0 || t35 == null || t35.isNegative()) {
            throw new IllegalArgumentException("BusTiming: baud " + baud + ", bits " + bitsPerCharacter + ", t3.5 "
                    + t35);
        }
        this.baud = baud;
        this.bitsPerCharacter = bitsPerCharacter;
        this.t35 = t35;
    }

    /**
     * @param settings the bus
     * @return the timing at the bus's baud rate: 11 bits per character (register map), t3.5 = 1.75 ms above 19200
     *         baud (register map), else 3.5 character times
     */
    public static BusTiming of(BusSettings settings) {
        ModbusMap map = ModbusMap.standard();
        int bits = map.bitsPerCharacter();
        Duration t35 = settings.baud() > 19200 ? map.t35()
                : Duration.ofNanos(Math.round(3.5 * bits * 1e9 / settings.baud()));
        return new BusTiming(settings.baud(), bits, t35);
    }

    /** @return bytes of a 0x14 request with {@code subRequests} sub-requests */
    public static int readRequestBytes(int subRequests) {
        return FRAME_OVERHEAD + READ_SUB_REQUEST * subRequests;
    }

    /** @return bytes of a 0x14 answer to sub-requests of these register counts */
    public static int readAnswerBytes(int... registers) {
        int n = FRAME_OVERHEAD;
        for (int r : registers) {
            n += READ_SUB_ANSWER + 2 * r;
        }
        return n;
    }

    /** @return bytes of a 0x15 request (and of its echoed answer) with sub-requests of these register counts */
    public static int writeBytes(int... registers) {
        int n = FRAME_OVERHEAD;
        for (int r : registers) {
            n += READ_SUB_REQUEST + 2 * r;
        }
        return n;
    }

    /** @return the time of one character on the line */
    public Duration characterTime() {
        return Duration.ofNanos(Math.round(bitsPerCharacter * 1e9 / baud));
    }

    /** @return the inter-frame silence t3.5 */
    public Duration t35() {
        return t35;
    }

    /** @return (request + answer bytes) × bits / baud + t3.5 */
    public Duration wireTime(int requestBytes, int answerBytes) {
        return Duration.ofNanos(Math.round((requestBytes + answerBytes) * (double) bitsPerCharacter * 1e9 / baud))
                .plus(t35);
    }

    /** @return the wire time of a 0x14 transaction with sub-requests of these register counts */
    public Duration readTime(int... registers) {
        return wireTime(readRequestBytes(registers.length), readAnswerBytes(registers));
    }

    /** @return the wire time of a 0x15 transaction with sub-requests of these register counts */
    public Duration writeTime(int... registers) {
        return wireTime(writeBytes(registers), writeBytes(registers));
    }

    @Override
    public String toString() {
        return baud + " baud, " + bitsPerCharacter + " bits/char, t3.5 " + t35.toNanos() / 1000 + " µs";
    }
}
