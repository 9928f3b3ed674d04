package sabot.fleet;

import java.net.InetAddress;

import org.jivesoftware.smack.ConnectionConfiguration.SecurityMode;
import org.jivesoftware.smack.SASLAuthentication;
import org.jivesoftware.smack.java7.XmppHostnameVerifier;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smack.tcp.XMPPTCPConnectionConfiguration;
import org.jxmpp.jid.DomainBareJid;
import org.jxmpp.stringprep.XmppStringprepException;

import sabot.fleet.internal.ScramSha256Mechanism;

/**
 * Connection settings every Sabot client (robot or workbench) needs: TLS required, the server's certificate checked
 * against a {@link ServerTrust} and against the XMPP domain (never a plain or unchecked fallback); TCP_NODELAY sockets
 * (Smack leaves Nagle's algorithm on, which with delayed ACKs costs about 40 ms per request) and stream management
 * with resumption, so that a dropped network does not lose commands (XEP-0198).
 */
public final class FleetConnections {

    static {
        // Smack 4.4 has SCRAM-SHA-1 only; servers that store SHA-256 password hashes offer SCRAM-SHA-256 alone
        // (with PLAIN inside TLS, which Smack would otherwise choose)
        if (!SASLAuthentication.isSaslMechanismRegistered(ScramSha256Mechanism.NAME)) {
            SASLAuthentication.registerSASLMechanism(new ScramSha256Mechanism());
        }
    }

    private FleetConnections() {
    }

    /**
     * @param domain the XMPP domain, e.g. {@code sabot.local}: the name the server's certificate must carry
     * @param host   the server's address (no DNS lookup)
     * @param port   the c2s port
     * @param trust  whom to trust for the server's certificate
     * @return a builder with TLS required, TCP_NODELAY and the given endpoint; add credentials and resource, then build
     */
    public static XMPPTCPConnectionConfiguration.Builder builder(String domain, InetAddress host, int port,
            ServerTrust trust) throws XmppStringprepException {
        XMPPTCPConnection.setUseStreamManagementDefault(true);
        XMPPTCPConnection.setUseStreamManagementResumptionDefault(true);
        return secured(XMPPTCPConnectionConfiguration.builder().setXmppDomain(DomainBareJid.class.cast(
                org.jxmpp.jid.impl.JidCreate.domainBareFrom(domain))).setHostAddress(host).setPort(port)
                .setSocketFactory(new NoDelaySocketFactory()), trust);
    }

    /**
     * @return {@code builder} with TLS required, {@code trust}'s context and the XMPP host name check (RFC 6125: the
     *         certificate must name the XMPP domain, whatever address the socket went to)
     */
    public static XMPPTCPConnectionConfiguration.Builder secured(XMPPTCPConnectionConfiguration.Builder builder,
            ServerTrust trust) {
        // Smack makes a TLS context per connection and initialises it with this trust manager
        return builder.setSecurityMode(SecurityMode.required).setCustomX509TrustManager(trust.trustManager())
                .setHostnameVerifier(new XmppHostnameVerifier());
    }
}
