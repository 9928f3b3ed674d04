package sabot.controlml;

import org.osgi.annotation.versioning.ConsumerType;

/**
 * Serves gets of one resource on a device. Runs on the connection's ordered request thread: return quickly.
 *
 * @param <T> the resource's value
 * @param <Q> the get's query ({@link sabot.controlml.payload.NoQuery#NONE} when it takes none)
 */
@FunctionalInterface
@ConsumerType
public interface GetHandler<T, Q> {

    /**
     * @param request who asks
     * @param query   the decoded query; never null
     * @return the value (a success must carry one) or an error
     */
    Outcome<T> get(Request request, Q query);
}
