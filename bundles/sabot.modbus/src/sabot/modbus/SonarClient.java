package sabot.modbus;

import java.io.IOException;
import java.time.Duration;
import java.util.List;

import org.osgi.annotation.versioning.ProviderType;

/** The sonar board (slave 3). Each method is one transaction; failures are {@link BoardException}s. */
@ProviderType
public interface SonarClient extends Board {

    /** @return how many sensors the register map describes (3) */
    int sensorCount();

    /**
     * @param sensor 0 … {@link #sensorCount()} − 1
     * @return that sensor's latest reading
     * @throws IllegalArgumentException no such sensor
     */
    SonarReading readSensor(int sensor) throws IOException;

    /** @return every sensor's latest reading, in sensor order, from one sub-request */
    List<SonarReading> readSensors() throws IOException;

    /** @return the wire time of {@link #readSensor(int)} */
    Duration readSensorWireTime();
}
