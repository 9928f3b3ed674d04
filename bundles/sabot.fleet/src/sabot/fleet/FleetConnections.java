package sabot.fleet;

import java.net.InetAddress;

import org.jivesoftware.smack.ConnectionConfiguration.SecurityMode;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smack.tcp.XMPPTCPConnectionConfiguration;
import org.jxmpp.jid.DomainBareJid;
import org.jxmpp.stringprep.XmppStringprepException;

/**
 * Connection settings every Sabot client (robot or workbench) needs: TCP_NODELAY sockets (Smack leaves Nagle's
 * algorithm on, which with delayed ACKs costs about 40 ms per request) and stream management with resumption, so that
 * a dropped network does not lose commands (XEP-0198).
 */
public final class FleetConnections {

    private FleetConnections() {
    }

    /**
     * @param domain   the XMPP domain, e.g. {@code sabot.local}
     * @param host     the server's address (no DNS lookup)
     * @param port     the c2s port
     * @param security {@code required} in production; {@code disabled} only on loopback test servers
     * @return a builder with TCP_NODELAY and the given endpoint; add credentials and resource, then build
     */
    public static XMPPTCPConnectionConfiguration.Builder builder(String domain, InetAddress host, int port,
            SecurityMode security) throws XmppStringprepException {
        XMPPTCPConnection.setUseStreamManagementDefault(true);
        XMPPTCPConnection.setUseStreamManagementResumptionDefault(true);
        return XMPPTCPConnectionConfiguration.builder().setXmppDomain(DomainBareJid.class.cast(
                org.jxmpp.jid.impl.JidCreate.domainBareFrom(domain))).setHostAddress(host).setPort(port)
                .setSecurityMode(security).setSocketFactory(new NoDelaySocketFactory());
    }
}
