package sabot.controlml;

import org.jxmpp.jid.EntityBareJid;
import org.osgi.annotation.versioning.ConsumerType;

/**
 * Receives a resource's telemetry from the devices this client is subscribed to (PEP notifications).
 *
 * @param <T> the resource's value
 */
@FunctionalInterface
@ConsumerType
public interface TelemetryListener<T> {

    /**
     * Called on Smack's ordered per-publisher thread.
     *
     * @param device the publishing device's bare JID
     * @param value  the decoded value
     */
    void onTelemetry(EntityBareJid device, T value);
}
