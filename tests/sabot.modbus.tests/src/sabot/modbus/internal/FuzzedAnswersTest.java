package sabot.modbus.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.net.SocketTimeoutException;
import java.time.Duration;
import java.util.Arrays;
import java.util.EnumMap;
import java.util.HashSet;
import java.util.Map;
import java.util.Random;
import java.util.Set;
import java.util.concurrent.atomic.AtomicReference;

import org.junit.jupiter.api.Test;

import sabot.modbus.BoardException;
import sabot.modbus.BusSettings;
import sabot.modbus.Motor;
import sabot.modbus.PowerReading;
import sabot.modbus.SactClient;

/**
 * The master's answer parsing fuzzed (a property-based test with a fixed seed, no fuzzing engine): a slave on a
 * loopback socket answers each request with a mutation of the right answer — bits flipped, cut short, grown, a wrong
 * byte count, a wrong function code or slave, random bytes, or nothing. Whatever comes back, every call of the SACT
 * client ends in its result or a {@link BoardException}, never in another exception, and within its attempt's timeout;
 * an unmutated answer is never refused as bad, and silence, a cut frame or one to three flipped bits are never taken
 * (the CRC is checked over TCP too). The bus stays usable afterwards. An answer with bytes after its CRC is taken:
 * RTU frames end at the silence, and the bytes are dropped before the next request.
 */
class FuzzedAnswersTest {

    /** Answers mutated per run. */
    private static final int ROUNDS = 500;
    /**
     * The master's answer timeout: the slave is a thread of the test's JVM, so the timeout leaves room for it to be
     * scheduled on a busy machine (an answer taken too late would count as refused).
     */
    private static final Duration TIMEOUT = Duration.ofMillis(50);

    enum Mutation {
        NONE, FLIP_BITS, CUT, GROW, BYTE_COUNT, FUNCTION, SLAVE, RANDOM, SILENCE, VALID_CRC_GARBAGE;

        /** Each mutation's share of the rounds: those that cost a whole timeout (nothing, or half a frame) less. */
        int weight() {
            return this == SILENCE || this == CUT ? 1 : 3;
        }
    }

    private static Mutation pick(Random random) {
        int total = 0;
        for (Mutation m : Mutation.values()) {
            total += m.weight();
        }
        int r = random.nextInt(total);
        for (Mutation m : Mutation.values()) {
            r -= m.weight();
            if (r < 0) {
                return m;
            }
        }
        throw new IllegalStateException();
    }

    @Test
    void noAnswerEscapesTheBusAsAnythingButABoardException() throws Exception {
        Random random = new Random(20261128);
        try (FuzzingSlave slave = new FuzzingSlave(random)) {
            BusSettings settings = BusSettings.tcp("127.0.0.1", slave.port()).withResponseTimeout(TIMEOUT)
                    .withRetries(0).withInterFrameDelay(Duration.ofNanos(1_750_000));
            Bus bus = Bus.open(settings);
            try {
                SactClient sact = bus.sact();
                Map<Mutation, int[]> outcomes = new EnumMap<>(Mutation.class); // {ok, board exception}
                long worstNanos = 0;
                Mutation previous = null;
                int unansweredGood = 0;
                for (int i = 0; i < ROUNDS; i++) {
                    Mutation m = pick(random);
                    slave.next.set(m);
                    long t0 = System.nanoTime();
                    boolean ok;
                    BoardException.Kind refused = null;
                    try {
                        switch (i % 4) {
                            case 0 -> sact.readWheels();
                            case 1 -> sact.setWheelSpeeds(random.nextDouble() - 0.5, random.nextDouble() - 0.5);
                            case 2 -> sact.readPositions();
                            default -> sact.readGains(random.nextBoolean() ? Motor.LEFT : Motor.RIGHT);
                        }
                        ok = true;
                    } catch (BoardException e) {
                        ok = false;
                        refused = e.kind();
                    } catch (IOException | RuntimeException e) {
                        throw new AssertionError("round " + i + ", " + m + ": " + e, e);
                    }
                    worstNanos = Math.max(worstNanos, System.nanoTime() - t0);
                    outcomes.computeIfAbsent(m, k -> new int[2])[ok ? 0 : 1]++;
                    previous = m;
                    if (m == Mutation.NONE && !ok) {
                        // the slave is a thread of this JVM: on a starved machine its answer may come after the
                        // timeout, which is the bus's business; refusing a good answer as bad never is
                        assertEquals(BoardException.Kind.TIMEOUT, refused, "round " + i + ": an unmutated answer was "
                                + "refused as " + refused + " (the round before: " + previous + ")");
                        unansweredGood++;
                    }
                }
                System.out.println("[fuzz] outcomes per mutation {taken, board exception}: " + describe(outcomes)
                        + "; slowest call " + worstNanos / 1_000_000 + " ms; unmutated answers too late: "
                        + unansweredGood);
                // no hang: a call is one attempt, its timeout and the silence before it (a hang would be the
                // socket's or a parser's loop, far beyond this bound)
                assertTrue(worstNanos < TIMEOUT.toNanos() + 2_000_000_000L, "a call took " + worstNanos / 1e6 + " ms");
                for (Mutation never : new Mutation[] { Mutation.SILENCE, Mutation.CUT, Mutation.FLIP_BITS }) {
                    assertEquals(0, outcomes.getOrDefault(never, new int[2])[0], never + " taken as an answer");
                }
                // the bus is still usable (a late answer on a starved machine is a timeout, not a broken bus)
                slave.next.set(Mutation.NONE);
                for (int attempt = 1;; attempt++) {
                    try {
                        sact.readGains(Motor.LEFT);
                        break;
                    } catch (BoardException e) {
                        if (e.kind() != BoardException.Kind.TIMEOUT || attempt == 3) {
                            throw e;
                        }
                    }
                }
            } finally {
                bus.close();
            }
        }
    }

    private static String describe(Map<Mutation, int[]> outcomes) {
        StringBuilder sb = new StringBuilder();
        outcomes.forEach((m, c) -> sb.append(m).append(' ').append(Arrays.toString(c)).append(' '));
        return sb.toString().trim();
    }

    /**
     * An RTU-over-TCP slave that answers every request (0x14 reads with random registers, 0x15 writes with their echo)
     * after applying the mutation the test set for it.
     */
    /**
     * The power board's answers with every register random (well-formed frames, right CRC): each read is a reading
     * within the register map's bounds or a {@link BoardException} of kind IMPLAUSIBLE naming the record, never
     * another exception and never an out-of-range value taken.
     */
    @Test
    void randomPowerRegistersAreEitherWithinTheMapOrRefusedAsImplausible() throws Exception {
        Random random = new Random(20261201);
        try (FuzzingSlave slave = new FuzzingSlave(random)) {
            BusSettings settings = BusSettings.tcp("127.0.0.1", slave.port()).withResponseTimeout(Duration.ofMillis(
                    200)).withRetries(1);
            Bus bus = Bus.open(settings);
            slave.smallValues = true; // after the SACT's configuration, read at the open
            try {
                int taken = 0;
                int implausible = 0;
                for (int i = 0; i < 200; i++) {
                    try {
                        PowerReading r = bus.power().readLatest();
                        assertTrue(r.stateOfCharge() >= 0 && r.stateOfCharge() <= 1, r.toString());
                        taken++;
                    } catch (BoardException e) {
                        assertEquals(BoardException.Kind.IMPLAUSIBLE, e.kind(), e.getMessage());
                        assertTrue(e.getMessage().matches("power: (state_of_charge \\d+ is outside the register map's "
                                + "bounds \\[0, 10000\\]|status 0x[0-9a-f]{4} sets bits the register map does not "
                                + "name \\(0x[0-9a-f]{4}\\))"), e.getMessage());
                        implausible++;
                    }
                }
                System.out.printf("[fuzz] power board: %d random readings taken, %d refused as implausible%n", taken,
                        implausible);
                assertTrue(taken > 0 && implausible > 0, taken + " taken, " + implausible + " refused");
            } finally {
                bus.close();
            }
        }
    }

    private static final class FuzzingSlave implements AutoCloseable {

        final AtomicReference<Mutation> next = new AtomicReference<>(Mutation.NONE);
        /** Registers read are 0–7 half the time, else any 16 bits; otherwise always any 16 bits. */
        volatile boolean smallValues;
        private final ServerSocket server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress());
        private final Random random;
        private final Thread thread;

        FuzzingSlave(Random seed) throws IOException {
            this.random = new Random(seed.nextLong());
            thread = new Thread(this::serve, "fuzzing-slave");
            thread.setDaemon(true);
            thread.start();
        }

        int port() {
            return server.getLocalPort();
        }

        private void serve() {
            try (Socket s = server.accept()) {
                s.setTcpNoDelay(true);
                InputStream in = s.getInputStream();
                OutputStream out = s.getOutputStream();
                while (true) {
                    byte[] request = readFrame(s, in);
                    if (request == null) {
                        return;
                    }
                    byte[] answer = mutate(answerTo(request), next.get());
                    if (answer.length > 0) {
                        out.write(answer);
                        out.flush();
                    }
                }
            } catch (IOException closed) {
                // the test closed the bus or the server
            }
        }

        /** @return the bytes of one request: all that arrives until 2 ms of silence; null at the end of the stream */
        private static byte[] readFrame(Socket s, InputStream in) throws IOException {
            ByteArrayOutputStream frame = new ByteArrayOutputStream();
            s.setSoTimeout(0);
            int b = in.read();
            if (b < 0) {
                return null;
            }
            frame.write(b);
            s.setSoTimeout(2);
            try {
                while ((b = in.read()) >= 0) {
                    frame.write(b);
                }
                return null;
            } catch (SocketTimeoutException silence) {
                return frame.toByteArray();
            }
        }

        /** @return the well-formed answer to a 0x14 or 0x15 request (an exception answer to anything else) */
        private byte[] answerTo(byte[] request) {
            int slave = request[0] & 0xff;
            int function = request.length > 1 ? request[1] & 0xff : 0;
            ByteArrayOutputStream a = new ByteArrayOutputStream();
            a.write(slave);
            if (function == 0x15 && request.length > 4) {
                a.write(request, 1, request.length - 3); // the echo, without the CRC
            } else if (function == 0x14 && request.length > 4) {
                int subRequests = ((request[2] & 0xff)) / 7;
                ByteArrayOutputStream data = new ByteArrayOutputStream();
                for (int k = 0; k < subRequests; k++) {
                    int count = ((request[3 + 7 * k + 5] & 0xff) << 8) | (request[3 + 7 * k + 6] & 0xff);
                    data.write(1 + 2 * count);
                    data.write(6);
                    for (int r = 0; r < count; r++) {
                        // small values half the time when asked: enough flags and fractions fall inside a map's bounds
                        if (smallValues && random.nextBoolean()) {
                            data.write(0);
                            data.write(random.nextInt(8));
                        } else {
                            data.write(random.nextInt(256));
                            data.write(random.nextInt(256));
                        }
                    }
                }
                a.write(0x14);
                a.write(data.size());
                a.writeBytes(data.toByteArray());
            } else {
                a.write(function | 0x80);
                a.write(1);
            }
            return withCrc(a.toByteArray());
        }

        private byte[] mutate(byte[] answer, Mutation m) {
            byte[] b = answer.clone();
            switch (m) {
                case NONE -> {
                    return b;
                }
                case FLIP_BITS -> {
                    // one to three distinct bits: the CRC-16 detects every such error in a frame this short
                    int bits = 1 + random.nextInt(3);
                    Set<Integer> flipped = new HashSet<>();
                    while (flipped.size() < bits) {
                        flipped.add(random.nextInt(8 * b.length));
                    }
                    for (int bit : flipped) {
                        b[bit / 8] ^= (byte) (1 << (bit % 8));
                    }
                    return b;
                }
                case CUT -> {
                    return Arrays.copyOf(b, random.nextInt(b.length));
                }
                case GROW -> {
                    byte[] g = Arrays.copyOf(b, b.length + 1 + random.nextInt(40));
                    for (int k = b.length; k < g.length; k++) {
                        g[k] = (byte) random.nextInt(256);
                    }
                    return g;
                }
                case BYTE_COUNT -> {
                    // a wrong length field, but a frame whose CRC is right: the parser must not trust it
                    if (b.length > 4) {
                        b[2] = (byte) random.nextInt(256);
                        if (b.length > 5 && random.nextBoolean()) {
                            b[3] = (byte) random.nextInt(256);
                        }
                    }
                    return withCrc(Arrays.copyOf(b, b.length - 2));
                }
                case FUNCTION -> {
                    b[1] = (byte) random.nextInt(256);
                    return withCrc(Arrays.copyOf(b, b.length - 2));
                }
                case SLAVE -> {
                    b[0] = (byte) (b[0] + 1 + random.nextInt(200));
                    return withCrc(Arrays.copyOf(b, b.length - 2));
                }
                case RANDOM -> {
                    byte[] r = new byte[random.nextInt(300)];
                    random.nextBytes(r);
                    return r;
                }
                case SILENCE -> {
                    return new byte[0];
                }
                case VALID_CRC_GARBAGE -> {
                    byte[] r = new byte[2 + random.nextInt(60)];
                    random.nextBytes(r);
                    r[0] = b[0];
                    r[1] = b[1];
                    return withCrc(r);
                }
                default -> throw new IllegalStateException(m.toString());
            }
        }

        /** @return {@code frame} with its Modbus CRC-16 appended, low byte first */
        private static byte[] withCrc(byte[] frame) {
            int crc = 0xffff;
            for (byte x : frame) {
                crc ^= x & 0xff;
                for (int k = 0; k < 8; k++) {
                    crc = (crc & 1) != 0 ? (crc >>> 1) ^ 0xa001 : crc >>> 1;
                }
            }
            byte[] out = Arrays.copyOf(frame, frame.length + 2);
            out[frame.length] = (byte) crc;
            out[frame.length + 1] = (byte) (crc >>> 8);
            return out;
        }

        @Override
        public void close() throws IOException {
            server.close();
        }
    }
}
