package sabot.onboard.portal.internal;

import java.time.Instant;
import java.time.ZoneOffset;
import java.time.format.DateTimeFormatter;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Deque;
import java.util.List;

import org.slf4j.LoggerFactory;

import ch.qos.logback.classic.Logger;
import ch.qos.logback.classic.LoggerContext;
import ch.qos.logback.classic.spi.ILoggingEvent;
import ch.qos.logback.core.AppenderBase;

/**
 * The product's last log lines for the status page: a Logback appender on the root logger keeping the last
 * {@value #LINES} lines (INFO and above, as etc/logback.xml lets them through), removed when the task stops.
 */
final class RecentLog extends AppenderBase<ILoggingEvent> {

    static final int LINES = 40;
    private static final DateTimeFormatter TIME = DateTimeFormatter.ofPattern("HH:mm:ss.SSS").withZone(ZoneOffset.UTC);

    private final Deque<String> lines = new ArrayDeque<>(LINES);

    /** @return the appender attached to the root logger, or null when SLF4J is not bound to Logback */
    static RecentLog attach() {
        if (!(LoggerFactory.getILoggerFactory() instanceof LoggerContext context)) {
            return null;
        }
        RecentLog log = new RecentLog();
        log.setContext(context);
        log.setName("sabot-portal-recent");
        log.start();
        context.getLogger(Logger.ROOT_LOGGER_NAME).addAppender(log);
        return log;
    }

    void detach() {
        if (getContext() instanceof LoggerContext context) {
            context.getLogger(Logger.ROOT_LOGGER_NAME).detachAppender(this);
        }
        stop();
    }

    @Override
    protected void append(ILoggingEvent event) {
        if (!event.getLevel().isGreaterOrEqual(ch.qos.logback.classic.Level.INFO)) {
            return;
        }
        String line = TIME.format(Instant.ofEpochMilli(event.getTimeStamp())) + " " + event.getLevel() + " "
                + shortName(event.getLoggerName()) + ": " + event.getFormattedMessage();
        synchronized (lines) {
            if (lines.size() == LINES) {
                lines.removeFirst();
            }
            lines.addLast(line.length() > 400 ? line.substring(0, 400) + "…" : line);
        }
    }

    /** @return the lines, oldest first */
    List<String> lines() {
        synchronized (lines) {
            return new ArrayList<>(lines);
        }
    }

    private static String shortName(String logger) {
        int dot = logger.lastIndexOf('.');
        return dot < 0 ? logger : logger.substring(dot + 1);
    }
}
