package sabot.fleet;

import org.jivesoftware.smack.packet.StanzaError;
import org.jxmpp.jid.EntityBareJid;
import org.osgi.annotation.versioning.ProviderType;

/** The outcome of a device registering its account. */
@ProviderType
public sealed interface RegistrationResult permits RegistrationResult.Registered, RegistrationResult.Taken,
        RegistrationResult.Refused {

    /** @param jid the new account */
    record Registered(EntityBareJid jid) implements RegistrationResult {
    }

    /** @param jid the account that already exists (XEP-0077 {@code conflict}) */
    record Taken(EntityBareJid jid) implements RegistrationResult {
    }

    /**
     * @param condition the server's reason (e.g. not-allowed when in-band registration is off), or null when the
     *                  server could not be reached
     * @param text      details for a human
     */
    record Refused(StanzaError.Condition condition, String text) implements RegistrationResult {
    }
}
