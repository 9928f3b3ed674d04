package sabot.controlml.bench;

import java.util.List;

import org.jxmpp.jid.EntityBareJid;

/** The load robots as the benchmarks see them: in this JVM ({@link FleetLoad}) or in a process of their own ({@link LoadProcess}). */
interface Load extends AutoCloseable {

    /** @return the robots' bare JIDs, in order */
    List<EntityBareJid> jids();

    /** @return the robots' telemetry publications the server acknowledged so far */
    long telemetryPublished();

    /** @return the robots' telemetry publications that failed so far (refused, timed out or not sent) */
    long telemetryFailed();

    /** Stops the robots (their connections closed). */
    @Override
    void close();
}
