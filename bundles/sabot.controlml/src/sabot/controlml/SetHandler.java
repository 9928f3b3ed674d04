package sabot.controlml;

import org.osgi.annotation.versioning.ConsumerType;

/**
 * Applies sets of one resource on a device. Called only with a value that passed the schema, the access policy, the
 * stale-command policy and the duplicate check; called at most once per requester and id. Runs on the connection's
 * ordered request thread, so sets apply in arrival order.
 *
 * @param <T> the resource's value
 */
@FunctionalInterface
@ConsumerType
public interface SetHandler<T> {

    /**
     * @param request who commands
     * @param value   the decoded value; never null
     * @return {@link Outcome#done()}, a success with the value read back, or an error (then the device's state must
     *         be as before)
     */
    Outcome<T> set(Request request, T value);
}
