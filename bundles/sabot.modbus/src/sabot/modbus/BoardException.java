package sabot.modbus;

import java.io.IOException;

/** A transaction with one board failed. The board's name and the kind of failure say what to do about it. */
public class BoardException extends IOException {

    private static final long serialVersionUID = 1L;

    /** What went wrong. */
    public enum Kind {
        /** no answer within the response timeout on every attempt */
        TIMEOUT,
        /** answers arrived but with a bad CRC, or not a valid answer to the request, on every attempt */
        MALFORMED,
        /** the board answered with a Modbus exception ({@link #exceptionCode()}) */
        EXCEPTION,
        /** the board has had no good answer for longer than the bus's {@code faultAfter}; this attempt failed too */
        FAULTED,
        /** a well-formed answer whose value no working board gives: outside the register map's bounds */
        IMPLAUSIBLE
    }

    /**
     * Modbus exception 4: the board could not do what was asked. The SACT board answers it to a non-zero wheel
     * set-point while a motor fault is latched (docs/SACT-MODBUS.md).
     */
    public static final int SERVER_DEVICE_FAILURE = 4;

    private final String board;
    private final Kind kind;
    private final int exceptionCode;

    /**
     * @param board         the board's name in the register map (sact, ins, sonar, landmark, power)
     * @param kind          what went wrong
     * @param exceptionCode the Modbus exception code for {@link Kind#EXCEPTION}, else 0
     * @param message       what happened, for a person
     */
    public BoardException(String board, Kind kind, int exceptionCode, String message) {
        super(board + ": " + message);
        this.board = board;
        this.kind = kind;
        this.exceptionCode = exceptionCode;
    }

    /** @return the board's name in the register map: sact, ins, sonar, landmark or power */
    public String board() {
        return board;
    }

    /** @return what went wrong */
    public Kind kind() {
        return kind;
    }

    /**
     * @return the Modbus exception code (1 illegal function, 2 illegal data address, 3 illegal data value, 4 server
     *         device failure) for {@link Kind#EXCEPTION}, else 0
     */
    public int exceptionCode() {
        return exceptionCode;
    }

    /** @return whether the board answered {@link #SERVER_DEVICE_FAILURE} */
    public boolean isServerDeviceFailure() {
        return kind == Kind.EXCEPTION && exceptionCode == SERVER_DEVICE_FAILURE;
    }
}
