package sabot.modbus.internal;

import java.io.IOException;
import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.locks.ReentrantLock;

import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import com.ghgande.j2mod.modbus.msg.ExceptionResponse;
import com.ghgande.j2mod.modbus.msg.ModbusRequest;
import com.ghgande.j2mod.modbus.msg.ModbusResponse;
import com.ghgande.j2mod.modbus.msg.ReadFileRecordRequest;
import com.ghgande.j2mod.modbus.msg.ReadFileRecordResponse;
import com.ghgande.j2mod.modbus.msg.WriteFileRecordRequest;
import com.ghgande.j2mod.modbus.msg.WriteFileRecordResponse;

import sabot.modbus.BoardCounters;
import sabot.modbus.BoardException;
import sabot.modbus.BusSettings;
import sabot.modbus.BusStatistics;
import sabot.modbus.BusTiming;
import sabot.modbus.InsClient;
import sabot.modbus.LandmarkClient;
import sabot.modbus.ModbusBus;
import sabot.modbus.PowerClient;
import sabot.modbus.SactClient;
import sabot.modbus.SonarClient;

/**
 * One bus: the {@link Line}, the lock that serialises its transactions, the retry loop and each board's counters.
 */
public final class Bus implements ModbusBus {

    private static final Logger LOG = LoggerFactory.getLogger(Bus.class);

    /** A write sub-request: {@code values} from {@code record} of {@code file}. */
    record Write(int file, int record, short[] values) {
    }

    /** Counters and fault clock of one board. */
    final class Counters {
        final String board;
        final int slave;
        final AtomicLong sent = new AtomicLong();
        final AtomicLong answers = new AtomicLong();
        final AtomicLong crc = new AtomicLong();
        final AtomicLong timeouts = new AtomicLong();
        final AtomicLong exceptions = new AtomicLong();
        volatile long lastGoodNanos;
        volatile Instant lastGood;
        volatile boolean lastFailed;
        /** When the current run of failed transactions began and when its latest one ended (System.nanoTime). */
        volatile long firstFailureNanos;
        volatile long lastFailureNanos;

        Counters(String board) {
            this.board = board;
            this.slave = map.slave(board);
        }

        /**
         * A board is faulted when its transactions have kept failing for longer than {@code faultAfter}, measured from
         * the first failure of the run to the latest one: a board polled rarely (the inertial board in a control
         * loop's spare time) is not faulted by one lost answer, and a board that is polled keeps a bounded detection
         * time (faultAfter plus one polling interval).
         */
        boolean faulted() {
            return lastFailed && lastFailureNanos - firstFailureNanos > settings.faultAfter().toNanos();
        }

        void failed() {
            long now = System.nanoTime();
            if (!lastFailed) {
                firstFailureNanos = now;
            }
            lastFailureNanos = now;
            lastFailed = true;
        }

        BoardCounters snapshot() {
            return new BoardCounters(board, sent.get(), answers.get(), crc.get(), timeouts.get(), exceptions.get(),
                    lastGood, faulted());
        }
    }

    private final BusSettings settings;
    private final ModbusMap map;
    private final Line line;
    private final BusTiming timing;
    private final ReentrantLock lock = new ReentrantLock(true);
    private final SactDriver sact;
    private final InsDriver ins;
    private final SonarDriver sonar;
    private final LandmarkDriver landmark;
    private final PowerDriver power;
    private volatile boolean closed;

    private Bus(BusSettings settings, ModbusMap map, Line line) {
        this.settings = settings;
        this.map = map;
        this.line = line;
        this.timing = BusTiming.of(settings);
        this.sact = new SactDriver(this, new Counters("sact"));
        this.ins = new InsDriver(this, new Counters("ins"));
        this.sonar = new SonarDriver(this, new Counters("sonar"));
        this.landmark = new LandmarkDriver(this, new Counters("landmark"));
        this.power = new PowerDriver(this, new Counters("power"));
    }

    /** Opens the line and reads the SACT configuration (see {@link sabot.modbus.ModbusBuses#open}). */
    public static Bus open(BusSettings settings) throws IOException {
        ModbusMap map = ModbusMap.standard();
        Bus bus = new Bus(settings, map, Line.open(settings));
        try {
            bus.sact.config();
        } catch (BoardException e) {
            LOG.warn("bus {} open, but the SACT configuration could not be read yet: {}", settings.where(),
                    e.getMessage());
        }
        LOG.info("Modbus bus {} open ({}, timeout {} ms x {} attempts)", settings.where(), settings.parity(),
                settings.responseTimeout().toMillis(), settings.retries() + 1);
        return bus;
    }

    ModbusMap map() {
        return map;
    }

    /** Reads the spans of one board in one 0x14 request; one register array per span. */
    short[][] read(Counters board, Span... spans) throws BoardException {
        ReadFileRecordRequest req = new ReadFileRecordRequest();
        req.setUnitID(board.slave);
        for (Span s : spans) {
            req.addRequest(new ReadFileRecordRequest.RecordRequest(s.file(), s.record(), s.count()));
        }
        int[] counts = new int[spans.length];
        for (int i = 0; i < spans.length; i++) {
            counts[i] = spans[i].count();
        }
        ModbusResponse response = transact(board, req, BusTiming.readAnswerBytes(counts), r -> {
            if (!(r instanceof ReadFileRecordResponse rr) || rr.getRecordCount() != spans.length) {
                return "not an answer to a read of " + spans.length + " sub-requests";
            }
            for (int i = 0; i < spans.length; i++) {
                if (rr.getRecord(i).getWordCount() != spans[i].count()) {
                    return "sub-answer " + i + " has " + rr.getRecord(i).getWordCount() + " registers, asked "
                            + spans[i].count();
                }
            }
            return null;
        });
        ReadFileRecordResponse rr = (ReadFileRecordResponse) response;
        short[][] out = new short[spans.length][];
        for (int i = 0; i < spans.length; i++) {
            ReadFileRecordResponse.RecordResponse rec = rr.getRecord(i);
            out[i] = new short[rec.getWordCount()];
            for (int k = 0; k < out[i].length; k++) {
                out[i][k] = rec.getRegister(k).toShort();
            }
        }
        return out;
    }

    /** Writes the sub-requests to one board in one 0x15 request (the board validates all before changing any). */
    void write(Counters board, Write... writes) throws BoardException {
        WriteFileRecordRequest req = new WriteFileRecordRequest();
        req.setUnitID(board.slave);
        for (Write w : writes) {
            req.addRequest(new WriteFileRecordRequest.RecordRequest(w.file(), w.record(), w.values()));
        }
        int[] counts = new int[writes.length];
        for (int i = 0; i < writes.length; i++) {
            counts[i] = writes[i].values().length;
        }
        transact(board, req, BusTiming.writeBytes(counts), r -> r instanceof WriteFileRecordResponse wr
                && wr.getRequestCount() == writes.length ? null : "not the echo of a write of " + writes.length
                        + " sub-requests");
    }

    private interface Check {
        /** @return why the response is not an answer to the request, or null */
        String problem(ModbusResponse response);
    }

    /** @param answerBytes the length of the answer when it is not an exception, for the line's waits */
    private ModbusResponse transact(Counters board, ModbusRequest request, int answerBytes, Check check)
            throws BoardException {
        lock.lock();
        try {
            if (closed) {
                throw new BoardException(board.board, BoardException.Kind.TIMEOUT, 0, "the bus " + settings.where()
                        + " is closed");
            }
            BoardException.Kind failure = BoardException.Kind.TIMEOUT;
            String detail = "";
            int attempts = settings.retries() + 1;
            for (int i = 0; i < attempts; i++) {
                board.sent.incrementAndGet();
                Line.Attempt a = line.attempt(request, answerBytes);
                if (a instanceof Line.Attempt.Answer(ModbusResponse response)) {
                    String problem = response.getUnitID() != board.slave
                            ? "answer from slave " + response.getUnitID() + ", asked " + board.slave
                            : response.getFunctionCode() != request.getFunctionCode()
                                    && !(response instanceof ExceptionResponse)
                                            ? "answer with function code " + response.getFunctionCode() : null;
                    if (problem == null && !(response instanceof ExceptionResponse)) {
                        problem = check.problem(response);
                    }
                    if (problem != null) {
                        board.crc.incrementAndGet();
                        failure = BoardException.Kind.MALFORMED;
                        detail = problem;
                        continue;
                    }
                    board.answers.incrementAndGet();
                    board.lastGoodNanos = System.nanoTime();
                    board.lastGood = Instant.now();
                    board.lastFailed = false;
                    if (response instanceof ExceptionResponse ex) {
                        board.exceptions.incrementAndGet();
                        throw new BoardException(board.board, BoardException.Kind.EXCEPTION, ex.getExceptionCode(),
                                "Modbus exception " + ex.getExceptionCode() + " (" + exceptionName(
                                        ex.getExceptionCode()) + ") to function 0x"
                                        + Integer.toHexString(request.getFunctionCode()));
                    }
                    return response;
                } else if (a instanceof Line.Attempt.Corrupt(String d)) {
                    board.crc.incrementAndGet();
                    failure = BoardException.Kind.MALFORMED;
                    detail = d;
                } else if (a instanceof Line.Attempt.Unanswered(String d)) {
                    board.timeouts.incrementAndGet();
                    failure = BoardException.Kind.TIMEOUT;
                    detail = d;
                }
            }
            board.failed();
            boolean faulted = board.faulted();
            throw new BoardException(board.board, faulted ? BoardException.Kind.FAULTED : failure, 0,
                    (faulted ? "faulted (no good answer for more than " + settings.faultAfter().toMillis()
                            + " ms); last attempt: " : "")
                            + (failure == BoardException.Kind.TIMEOUT ? "no answer" : "corrupt answers") + " on "
                            + settings.where() + " after " + attempts + " attempt(s) of "
                            + settings.responseTimeout().toMillis() + " ms (" + detail + ")");
        } finally {
            lock.unlock();
        }
    }

    private String exceptionName(int code) {
        List<String> names = new ArrayList<>(List.of("illegal_function", "illegal_data_address",
                "illegal_data_value", "server_device_failure"));
        for (String n : names) {
            if (map.exception(n) == code) {
                return n.replace('_', ' ');
            }
        }
        return "unknown";
    }

    @Override
    public SactClient sact() {
        return sact;
    }

    @Override
    public InsClient ins() {
        return ins;
    }

    @Override
    public SonarClient sonar() {
        return sonar;
    }

    @Override
    public LandmarkClient landmark() {
        return landmark;
    }

    @Override
    public PowerClient power() {
        return power;
    }

    @Override
    public BusStatistics statistics() {
        return new BusStatistics(sact.counters(), ins.counters(), sonar.counters(), landmark.counters(),
                power.counters());
    }

    @Override
    public BusSettings settings() {
        return settings;
    }

    @Override
    public BusTiming timing() {
        return timing;
    }

    @Override
    public void close() {
        lock.lock();
        try {
            if (!closed) {
                closed = true;
                line.close();
                LOG.info("Modbus bus {} closed", settings.where());
            }
        } finally {
            lock.unlock();
        }
    }
}
