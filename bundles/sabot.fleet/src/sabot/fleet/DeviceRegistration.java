package sabot.fleet;

import java.io.IOException;

import org.jivesoftware.smack.SmackException;
import org.jivesoftware.smack.XMPPException;
import org.jivesoftware.smack.packet.StanzaError;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smack.tcp.XMPPTCPConnectionConfiguration;
import org.jivesoftware.smackx.iqregister.AccountManager;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.impl.JidCreate;
import org.jxmpp.jid.parts.Localpart;

/**
 * A device creates its own account with in-band registration (XEP-0077). A JID that is already taken is refused by
 * the server ({@code conflict}) and reported as {@link RegistrationResult.Taken}, never overwritten.
 */
public final class DeviceRegistration {

    private DeviceRegistration() {
    }

    /**
     * @param config   where to connect (credentials are not used for the anonymous registration stream)
     * @param localpart the device's wanted name
     * @param password its password
     * @param allowInsecure true to send the password over an unencrypted stream (loopback test servers only)
     * @return what happened; never throws for a refusal
     */
    public static RegistrationResult register(XMPPTCPConnectionConfiguration config, String localpart,
            String password, boolean allowInsecure) {
        EntityBareJid jid;
        try {
            jid = JidCreate.entityBareFrom(localpart + "@" + config.getXMPPServiceDomain());
        } catch (IOException e) {
            return new RegistrationResult.Refused(StanzaError.Condition.jid_malformed, "not a JID: " + localpart);
        }
        XMPPTCPConnection anonymous = new XMPPTCPConnection(config);
        try {
            anonymous.connect();
            AccountManager accounts = AccountManager.getInstance(anonymous);
            accounts.sensitiveOperationOverInsecureConnection(allowInsecure);
            accounts.createAccount(Localpart.from(localpart), password);
            return new RegistrationResult.Registered(jid);
        } catch (XMPPException.XMPPErrorException e) {
            StanzaError.Condition c = e.getStanzaError().getCondition();
            if (c == StanzaError.Condition.conflict) {
                return new RegistrationResult.Taken(jid);
            }
            return new RegistrationResult.Refused(c, "the server refused to register " + jid + ": " + c);
        } catch (SmackException | IOException | XMPPException | InterruptedException e) {
            if (e instanceof InterruptedException) {
                Thread.currentThread().interrupt();
            }
            return new RegistrationResult.Refused(null, "registering " + jid + " failed: " + e);
        } finally {
            anonymous.disconnect();
        }
    }
}
