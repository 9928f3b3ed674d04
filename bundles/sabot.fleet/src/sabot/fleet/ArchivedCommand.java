package sabot.fleet;

import java.time.Duration;
import java.time.Instant;
import java.util.Objects;

/**
 * One command of a device's history in the server's archive ({@link CommandHistory}, docs/ARCHIVE.md).
 *
 * @param seq       its row in the archive (increasing)
 * @param at        when the server took it
 * @param stored    sent as a stored command (a message kept for a device that may be offline), else an IQ
 * @param resource  its ControlML resource, e.g. {@code cm.goal}
 * @param id        its ControlML id
 * @param from      who sent it (full JID)
 * @param answer    {@code result}, {@code error}, or empty: no answer archived
 * @param condition an error's condition, else empty
 * @param text      an error's text, else empty
 * @param answerIn  how long the answer took at the server, or null without one
 */
public record ArchivedCommand(long seq, Instant at, boolean stored, String resource, String id, String from,
        String answer, String condition, String text, Duration answerIn) {

    /** Checks the fields. */
    public ArchivedCommand {
        Objects.requireNonNull(at, "at");
        Objects.requireNonNull(resource, "resource");
        Objects.requireNonNull(id, "id");
        Objects.requireNonNull(from, "from");
        Objects.requireNonNull(answer, "answer");
        Objects.requireNonNull(condition, "condition");
        Objects.requireNonNull(text, "text");
    }
}
