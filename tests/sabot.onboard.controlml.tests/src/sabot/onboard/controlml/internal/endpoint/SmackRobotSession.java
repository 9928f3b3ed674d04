package sabot.onboard.controlml.internal.endpoint;

import java.util.List;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.atomic.AtomicLong;

import org.jivesoftware.smack.ConnectionListener;
import org.jivesoftware.smack.SmackException.NotConnectedException;
import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;

import sabot.controlml.ControlMlManager;
import sabot.controlml.PresenceLevel;
import sabot.onboard.session.RobotSession;
import sabot.onboard.session.SessionListener;

/**
 * A {@link RobotSession} over a plain Smack connection that the test opens, closes and logs in again itself (the
 * product's session, {@code sabot.task.controlml}, reconnects with back-off and publishes identity; neither matters
 * to the endpoint). It records every presence the endpoint sets and how often telemetry asked whether it is online.
 */
final class SmackRobotSession implements RobotSession {

    /** One {@link #setPresence} call. */
    record PresenceCall(PresenceLevel level, String reason) {
    }

    private final XMPPTCPConnection connection;
    private final String jid;
    private final List<SessionListener> listeners = new CopyOnWriteArrayList<>();
    private volatile PresenceCall presence;
    /** Every presence the endpoint set, in order. */
    final BlockingQueue<PresenceCall> presences = new LinkedBlockingQueue<>();
    /** How many times {@link #isOnline} was asked (each telemetry tick asks once). */
    final AtomicLong onlineChecks = new AtomicLong();

    SmackRobotSession(XMPPTCPConnection connection) {
        this.connection = connection;
        this.jid = connection.getConfiguration().getUsername() + "@" + connection.getXMPPServiceDomain();
        connection.addConnectionListener(new ConnectionListener() {
            @Override
            public void authenticated(XMPPConnection c, boolean resumed) {
                sendPresence(); // a new login starts without the level
                listeners.forEach(SessionListener::online);
            }

            @Override
            public void connectionClosed() {
                listeners.forEach(l -> l.offline("closed"));
            }

            @Override
            public void connectionClosedOnError(Exception e) {
                listeners.forEach(l -> l.offline(String.valueOf(e)));
            }
        });
    }

    @Override
    public String jid() {
        return jid;
    }

    @Override
    public XMPPConnection connection() {
        return connection;
    }

    @Override
    public ControlMlManager controlMl() {
        return ControlMlManager.getInstanceFor(connection);
    }

    @Override
    public boolean isOnline() {
        onlineChecks.incrementAndGet();
        return connection.isAuthenticated();
    }

    @Override
    public void setPresence(PresenceLevel level, String reason) {
        PresenceCall call = new PresenceCall(level, reason);
        presence = call;
        presences.add(call);
        sendPresence();
    }

    private void sendPresence() {
        PresenceCall p = presence;
        if (p == null || !connection.isAuthenticated()) {
            return;
        }
        try {
            connection.sendStanza(connection.getStanzaFactory().buildPresenceStanza().ofType(Presence.Type.available)
                    .setMode(p.level().mode()).setStatus(p.reason()).build());
        } catch (NotConnectedException e) {
            // sent again by authenticated() after the next login
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    @Override
    public void addListener(SessionListener listener) {
        listeners.add(listener);
    }

    @Override
    public void removeListener(SessionListener listener) {
        listeners.remove(listener);
    }

    @Override
    public PresenceLevel presenceLevel() {
        PresenceCall p = presence;
        return p == null ? PresenceLevel.FREE : p.level();
    }

    @Override
    public String presenceReason() {
        PresenceCall p = presence;
        return p == null || p.reason() == null ? "" : p.reason();
    }

    @Override
    public boolean checkPassword(String account, String password) {
        throw new UnsupportedOperationException("the endpoint's tests log nobody in");
    }

    @Override
    public List<String> lobbyMembers() {
        return List.of(); // the endpoint's tests join no lobby
    }
}
