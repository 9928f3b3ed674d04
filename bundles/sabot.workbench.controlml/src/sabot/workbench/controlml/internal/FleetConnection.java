package sabot.workbench.controlml.internal;

import java.io.IOException;
import java.net.InetAddress;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicInteger;

import org.jivesoftware.smack.ConnectionListener;
import org.jivesoftware.smack.ReconnectionManager;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.impl.JidCreate;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.ControlMlManager;
import sabot.fleet.FleetConnections;
import sabot.fleet.ServerTrust;
import sabot.fleet.LinkWatch;
import sabot.fleet.SubscriptionGate;
import sabot.workbench.account.XmppAccount;
import sabot.workbench.account.XmppAccountStore;
import sabot.workbench.fleet.Availability;
import sabot.workbench.fleet.ConnectionStatus.State;
import sabot.workbench.fleet.RobotState;

/**
 * The workbench's one XMPP connection, on its own thread: connects with the account of the preferences, logs in,
 * hands the session to the roster and the telemetry, and on a failure or a loss tries again after the
 * {@link Backoff}'s wait. The connection's state goes to the {@link RobotRegistry}.
 */
final class FleetConnection {

    /** Resource part of the workbench's full JID (several workbenches of one operator differ by a suffix). */
    static final String RESOURCE_PREFIX = "workbench-";
    /** Silence from the server after which it is pinged; twice it, the link is lost (as on the robots). */
    static final Duration LINK_LIVENESS = Duration.ofMillis(Math.round(LinkWatch.DEFAULT_INTERVAL_S * 1000));

    private static final Logger LOG = LoggerFactory.getLogger("sabot.workbench.controlml");

    private final ScheduledExecutorService connector;
    private final ThreadFactory watchThreads;
    private final Backoff backoff;
    private final FleetRequests requests;
    private final FleetTraffic traffic;
    /** Connection thread: which of the account's servers the next attempt goes to (modulo their number). */
    private int serverIndex;
    private final Duration requestTimeout;
    private final RobotRegistry registry;
    private final FleetRoster roster;
    private final FleetTelemetry telemetry;
    private final RobotMaps maps;
    private final AtomicInteger generation = new AtomicInteger();
    /** True while a reconnection is queued: the several keys of one account change make one reconnection. */
    private final AtomicBoolean reconnectQueued = new AtomicBoolean();
    /** The live session, touched on the connection thread only (read elsewhere). */
    private volatile FleetSession session;
    /** The connection thread (the connector's one thread), for {@link #silent} to interrupt its waits. */
    private volatile Thread connectorThread;
    /** The current session's watch on a silent link; connection thread only. */
    private LinkWatch linkWatch;
    /**
     * The attempt {@link #retry} scheduled; connection thread only. Each attempt cancels it: a reconnection for a
     * changed account must not be followed by the older account's retry, which would replace the new session.
     */
    private ScheduledFuture<?> pendingRetry;

    /**
     * @param watchThreads makes the thread of each session's {@link LinkWatch}
     */
    FleetConnection(ScheduledExecutorService connector, ThreadFactory watchThreads, Backoff backoff,
            Duration requestTimeout, RobotRegistry registry, FleetRoster roster, FleetTelemetry telemetry,
            RobotMaps maps, FleetRequests requests, FleetTraffic traffic) {
        this.requests = requests;
        this.traffic = traffic;
        this.connector = connector;
        this.watchThreads = watchThreads;
        this.backoff = backoff;
        this.requestTimeout = requestTimeout;
        this.registry = registry;
        this.roster = roster;
        this.telemetry = telemetry;
        this.maps = maps;
    }

    /** @return the session now live, or null */
    FleetSession session() {
        return session;
    }

    /** Connects on the connection thread. */
    void start() {
        connector.execute(this::connect);
    }

    /** Closes the session and stops the connection thread (waits up to 10 s for it). */
    void stop() {
        connector.execute(() -> {
            closeSession();
            registry.setStatus(State.STOPPED, registry.status().account(), "");
        });
        connector.shutdown();
        try {
            connector.awaitTermination(10, TimeUnit.SECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    /** Connects anew, at once, whatever the back-off said; several calls in a row make one reconnection. */
    void reconnect() {
        if (!connector.isShutdown() && reconnectQueued.compareAndSet(false, true)) {
            connector.execute(() -> {
                reconnectQueued.set(false);
                backoff.reset();
                serverIndex = 0;
                closeSession();
                connect();
            });
        }
    }

    /** Connection thread: connects with the stored account, or schedules the next attempt. */
    private void connect() {
        connectorThread = Thread.currentThread();
        if (pendingRetry != null) {
            pendingRetry.cancel(false); // this attempt replaces it (or is it)
            pendingRetry = null;
        }
        closeSession();
        XmppAccountStore store = XmppAccountStore.workbenchStore();
        XmppAccount account = store.load();
        String problem = account.problem();
        char[] password;
        try {
            password = store.loadPassword();
        } catch (IOException e) {
            registry.setStatus(State.NO_ACCOUNT, account.jid(), e.getMessage());
            return;
        }
        if (problem != null || password == null) {
            // without an account there is no fleet: the robots of a former account go
            registry.jids().forEach(registry::remove);
            registry.setStatus(State.NO_ACCOUNT, account.jid(), problem != null ? problem : "no password stored");
            return;
        }
        ServerTrust trust;
        try {
            trust = ServerTrust.of(account.caFile());
        } catch (IOException e) {
            registry.setStatus(State.NO_ACCOUNT, account.jid(), e.getMessage());
            return;
        }
        // one of the account's servers (a cluster's nodes): the same until an attempt there fails, then the next
        List<String> servers = account.servers();
        String server = servers.get(Math.floorMod(serverIndex, servers.size()));
        registry.setStatus(State.CONNECTING, account.jid(), server + ":" + account.port());
        XMPPTCPConnection c = null;
        try {
            EntityBareJid me = JidCreate.entityBareFrom(account.jid());
            c = new XMPPTCPConnection(FleetConnections.builder(me.getDomain().toString(), InetAddress.getByName(
                    server), account.port(), trust).setUsernameAndPassword(me
                            .getLocalpart().toString(), new String(password)).setResource(RESOURCE_PREFIX + Long
                                    .toHexString(System.nanoTime() & 0xffffff)).build());
            ReconnectionManager.getInstanceFor(c).disableAutomaticReconnection(); // our own back-off, below
            // Each attempt is a new connection, never a resumed stream: without resumption a request on a lost
            // connection fails at once instead of being queued for a resumption that never comes.
            c.setUseStreamManagementResumption(false);
            ControlMlManager manager = ControlMlManager.getInstanceFor(c);
            manager.setRequestTimeout(requestTimeout);
            // answers to stored commands sent by an earlier session (FleetState.goToWhenOnline) come here
            manager.addUnsolicitedAnswerListener((from, answer) -> requests.unsolicited(answer));
            Roster r = Roster.getInstanceFor(c);
            // One roster request at login, ours (reloadAndWait below). Smack would send another when authenticated:
            // the two results come back as asynchronous callbacks, and the later one, computed before a removal
            // whose push was handled in between, brought the removed robot back for good (LiveFleetUiTest's lobby
            // test, seen in CI and under load).
            r.setRosterLoadedAtLogin(false);
            FleetSession s = new FleetSession(c, manager, r, generation.incrementAndGet());
            telemetry.listen(s); // before login: +notify goes into the first presence's entity caps
            traffic.listen(c);
            SubscriptionGate.onWorkbench(c);
            roster.listen(s);
            c.addConnectionListener(new ConnectionListener() {
                @Override
                public void connectionClosedOnError(Exception e) {
                    connector.execute(() -> lost(s, "connection lost: " + describe(e)));
                }
            });
            // a silent network (nothing passes, nothing closes) greys the robots and reconnects within seconds
            linkWatch = new LinkWatch(c, LINK_LIVENESS, watchThreads, why -> silent(s, why));
            c.connect().login();
            linkWatch.online();
            r.reloadAndWait(); // the robots are known before the status says online
            session = s;
            roster.start(s, store.loadRobots(), store.loadLobby());
            backoff.reset();
            registry.setStatus(State.ONLINE, account.jid(), server + ":" + account.port());
            LOG.info("connected as {} to {}:{}; following {} robot(s)", c.getUser(), server, account.port(),
                    registry.jids().size());
            for (RobotState robot : registry.robots()) {
                if (robot.availability() != Availability.OFFLINE) {
                    telemetry.follow(s, robot.jid(), 0);
                }
            }
            roster.scheduleReconcile(s);
        } catch (Exception | LinkageError e) {
            // a LinkageError (a bundle missing from the runtime) would otherwise vanish in the executor
            if (e instanceof InterruptedException) {
                Thread.currentThread().interrupt();
            } else if (e instanceof LinkageError) {
                LOG.error("cannot connect: {}", e.toString(), e);
            }
            if (c != null) {
                c.instantShutdown();
            }
            if (linkWatch != null) {
                linkWatch.close();
                linkWatch = null;
            }
            session = null;
            serverIndex++; // the next of the account's servers, if it has several
            String certificate = trust.explain(e, account.jid().substring(account.jid().indexOf('@') + 1));
            retry(account.jid(), certificate != null ? certificate : describe(e));
        }
    }

    /**
     * Watch thread: the link went silent. The connection thread may be waiting out a request's timeout on the dead
     * link (a telemetry subscription, a roster reconciliation), so the loss is shown here at once: the connection is
     * shut (further requests fail at once instead of waiting), the status says why and the robots go grey; the
     * connection thread closes the session and retries when it is free.
     */
    private void silent(FleetSession s, String why) {
        if (session != s) {
            return;
        }
        s.connection().instantShutdown();
        registry.setStatus(State.RETRYING, registry.status().account(), why);
        for (String jid : registry.jids()) {
            registry.update(jid, r -> r.withPresence(Availability.OFFLINE, ""));
        }
        // A request the connection thread waits on ends at its timeout, which a shut connection does not shorten:
        // interrupt the wait (its code takes an interruption as a failed request; the executor clears the flag
        // before its next task, and an idle executor ignores it).
        Thread busy = connectorThread;
        if (busy != null) {
            busy.interrupt();
        }
        connector.execute(() -> lost(s, why));
    }

    private void lost(FleetSession s, String why) {
        if (session != s) {
            return; // an older connection's last words
        }
        closeSession();
        retry(registry.status().account(), why);
    }

    private void retry(String account, String why) {
        Duration wait = backoff.next();
        registry.setStatus(State.RETRYING, account, why + "; next attempt in " + wait.toMillis() / 1000.0 + " s");
        LOG.warn("XMPP connection of {}: {}; next attempt in {} ms", account, why, wait.toMillis());
        pendingRetry = connector.schedule(this::connect, wait.toMillis(), TimeUnit.MILLISECONDS);
    }

    private void closeSession() {
        FleetSession s = session;
        session = null;
        if (linkWatch != null) {
            linkWatch.close();
            linkWatch = null;
        }
        maps.clear();
        if (s != null) {
            s.connection().instantShutdown();
        }
        // nothing is known of the robots without a connection: they stay listed, offline
        for (String jid : registry.jids()) {
            registry.update(jid, r -> r.withPresence(Availability.OFFLINE, ""));
        }
    }

    private static String describe(Throwable e) {
        String m = e.getMessage();
        return e.getClass().getSimpleName() + (m == null ? "" : ": " + m);
    }
}
