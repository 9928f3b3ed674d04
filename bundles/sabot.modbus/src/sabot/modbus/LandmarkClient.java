package sabot.modbus;

import java.io.IOException;
import java.time.Duration;

import org.osgi.annotation.versioning.ProviderType;

/**
 * The ceiling-landmark board (slave 4): an up-looking camera at the robot centre that reads passive markers on the
 * ceiling and reports the nearest one within its view radius, once per period. Each method is one transaction;
 * failures are {@link BoardException}s.
 */
@ProviderType
public interface LandmarkClient extends Board {

    /** @return the latest measurement, read in one sub-request (consistent), its age computed by the board now */
    LandmarkSighting readLatest() throws IOException;

    /** @return the board's view radius and measurement period */
    LandmarkConfig readConfig() throws IOException;

    /**
     * Writes both settings in one request; the board takes both or neither.
     *
     * @throws IllegalArgumentException a value outside the register map's bounds (nothing is sent), or a null period
     */
    void writeConfig(LandmarkConfig config) throws IOException;

    /** @return the wire time of {@link #readLatest()} */
    Duration readLatestWireTime();
}
