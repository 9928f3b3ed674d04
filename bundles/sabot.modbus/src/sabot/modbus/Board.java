package sabot.modbus;

import java.time.Duration;

import org.osgi.annotation.versioning.ProviderType;

/** What every board client offers: its counters and fault state. */
@ProviderType
public interface Board {

    /** @return the board's counters now */
    BoardCounters counters();

    /** @return whether the board has had no good answer for longer than the bus's {@code faultAfter} */
    boolean faulted();

    /**
     * @return the wire time of this board's most frequent transaction (see each client), the figure a control loop
     *         budgets with
     */
    Duration typicalWireTime();
}
