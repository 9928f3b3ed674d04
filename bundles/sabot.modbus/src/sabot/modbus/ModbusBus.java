package sabot.modbus;

import org.osgi.annotation.versioning.ProviderType;

/**
 * One RS-485 bus and its five boards. One master, one line: every transaction on the bus is serialised, and the
 * clients may be used from any thread. Closing the bus closes the port; the clients then fail.
 */
@ProviderType
public interface ModbusBus extends AutoCloseable {

    /** @return the SACT motor board's client */
    SactClient sact();

    /** @return the inertial board's client */
    InsClient ins();

    /** @return the sonar board's client */
    SonarClient sonar();

    /** @return the ceiling-landmark board's client */
    LandmarkClient landmark();

    /** @return the power board's client (the battery) */
    PowerClient power();

    /** @return the counters of the five boards now */
    BusStatistics statistics();

    /** @return the settings the bus was opened with */
    BusSettings settings();

    /** @return the wire timing of this bus's line */
    BusTiming timing();

    /** Closes the port or socket. Idempotent. */
    @Override
    void close();
}
