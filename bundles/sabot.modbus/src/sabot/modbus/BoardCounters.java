package sabot.modbus;

import java.time.Instant;

/**
 * What one board's transactions came to since the bus opened. A snapshot; counts only grow.
 *
 * @param board           the board's name (sact, ins, sonar)
 * @param framesSent      request frames written, retries included
 * @param answers         valid answers received (Modbus exceptions included)
 * @param crcErrors       answers with a bad CRC or not a valid answer to the request
 * @param timeouts        attempts with no (complete) answer within the response timeout
 * @param exceptions      Modbus exception answers
 * @param lastGoodAnswer  when the last valid answer arrived; {@code null} when none has yet
 * @param faulted         whether the board has had no valid answer for longer than {@code faultAfter}
 */
public record BoardCounters(String board, long framesSent, long answers, long crcErrors, long timeouts,
        long exceptions, Instant lastGoodAnswer, boolean faulted) {
}
