package sabot.modbus;

import java.io.IOException;
import java.time.Duration;

import org.osgi.annotation.versioning.ProviderType;

/**
 * The power board (slave 5): the battery's voltage, current and state of charge, and whether the robot stands on a
 * charging dock, measured once per period. Each method is one transaction; failures are {@link BoardException}s.
 */
@ProviderType
public interface PowerClient extends Board {

    /**
     * @return the latest measurement, read in one sub-request (consistent)
     * @throws BoardException of kind {@link BoardException.Kind#IMPLAUSIBLE} when a value lies outside the register
     *                        map's bounds or a status bit the map does not name is set
     */
    PowerReading readLatest() throws IOException;

    /** @return the battery's design capacity and the measurement period */
    PowerConfig readConfig() throws IOException;

    /** @return the wire time of {@link #readLatest()} */
    Duration readLatestWireTime();
}
