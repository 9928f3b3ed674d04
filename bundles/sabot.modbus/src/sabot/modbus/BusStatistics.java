package sabot.modbus;

/**
 * The counters of the five boards of one bus, taken together.
 *
 * @param sact     the SACT motor board
 * @param ins      the inertial board
 * @param sonar    the sonar board
 * @param landmark the ceiling-landmark board
 * @param power    the power board
 */
public record BusStatistics(BoardCounters sact, BoardCounters ins, BoardCounters sonar, BoardCounters landmark,
        BoardCounters power) {
}
