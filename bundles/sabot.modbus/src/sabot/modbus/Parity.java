package sabot.modbus;

/** Parity of the serial line's characters. */
public enum Parity {
    /** no parity bit: a pseudo-terminal (Linux refuses parity on a pty; the simulator models the bits itself) */
    NONE,
    /** even parity: the robot's RS-485 line (8E1) */
    EVEN,
    /** odd parity */
    ODD
}
