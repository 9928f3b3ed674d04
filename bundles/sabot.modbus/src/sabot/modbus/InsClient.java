package sabot.modbus;

import java.io.IOException;
import java.time.Duration;

import org.osgi.annotation.versioning.ProviderType;

/** The inertial board (slave 2). Each method is one transaction; failures are {@link BoardException}s. */
@ProviderType
public interface InsClient extends Board {

    /** @return the latest full sample, read in one sub-request (consistent) */
    InsSample read() throws IOException;

    /** @return yaw rate and forward specific force only: a shorter transaction for a control loop */
    InsMotion readMotion() throws IOException;

    /** @return the wire time of {@link #read()} */
    Duration readWireTime();

    /** @return the wire time of {@link #readMotion()} */
    Duration readMotionWireTime();
}
