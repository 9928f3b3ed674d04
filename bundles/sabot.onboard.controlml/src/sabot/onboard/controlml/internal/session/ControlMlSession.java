package sabot.onboard.controlml.internal.session;

import java.io.IOException;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.TreeMap;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.ConnectionListener;
import org.jivesoftware.smack.SmackException;
import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.XMPPException;
import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smack.tcp.XMPPTCPConnectionConfiguration;
import org.osgi.framework.BundleContext;
import org.osgi.framework.ServiceReference;
import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;
import org.osgi.service.component.annotations.Deactivate;
import org.osgi.service.component.annotations.Reference;
import org.osgi.service.metatype.annotations.Designate;
import org.osgi.util.tracker.ServiceTracker;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.AccessPolicy;
import sabot.controlml.ControlMlManager;
import sabot.controlml.PresenceLevel;
import sabot.controlml.StaleCommandPolicy;
import sabot.fleet.Enrolment;
import sabot.fleet.FleetConnections;
import sabot.fleet.FleetException;
import sabot.fleet.LinkWatch;
import sabot.fleet.NoDelaySocketFactory;
import sabot.fleet.SubscriptionGate;
import sabot.identity.DeviceIdentityManager;
import sabot.identity.IdentityResult;
import sabot.identity.InventorySource;
import sabot.identity.QrInventory;
import sabot.onboard.task.NamedThreads;
import sabot.onboard.session.RobotSession;
import sabot.onboard.session.SessionListener;
import sabot.onboard.task.OnboardTask;

/**
 * The {@code controlml} task: the robot's XMPP session ({@link RobotSession}). One {@link XMPPTCPConnection} for the
 * component's life, so the {@link ControlMlManager} and the handlers registered on it survive reconnections.
 * <p>
 * Activation never waits for the network: the thread {@code sabot-session-connect} connects, and after a failed
 * attempt or a loss tries again after {@code reconnectMin}, doubling the delay up to {@code reconnectMax}, forever.
 * After each login it publishes the vCard identity with the QR inventory (again when the set of running tasks
 * changes), then sends the robot's presence (the last {@link #setPresence}; at first FREE "idle") and joins the fleet
 * lobby when one is configured ({@link SessionLobby}). Listeners are told on the thread {@code sabot-session-events},
 * in the order the changes happened.
 * <p>
 * Settings: {@link ControlMlSettings.Config}, read by {@link ControlMlSettings}; authorization: {@link OperatorPolicy}.
 */
@Designate(ocd = ControlMlSettings.Config.class, factory = false)
@Component(name = "sabot.task.controlml", configurationPolicy = ConfigurationPolicy.REQUIRE, immediate = true,
        service = { OnboardTask.class, RobotSession.class })
public final class ControlMlSession implements OnboardTask, RobotSession {

    private static final Logger LOG = LoggerFactory.getLogger(ControlMlSession.class);

    /** Failed attempts in a row logged one by one; later ones go to debug until the session is back. */
    static final int LOGGED_FAILURES = 3;
    /** How long a connection attempt may wait for the server's TCP accept and stream. */
    static final Duration CONNECT_TIMEOUT = Duration.ofSeconds(10);
    /** Tasks start in a burst: the identity is published again once the set of tasks has been still this long. */
    static final Duration IDENTITY_SETTLE = Duration.ofSeconds(1);

    private final ControlMlSettings settings;
    private final InventorySource inventorySource;
    private final String version;
    private final XMPPTCPConnection connection;
    /** The sockets: TCP_NODELAY, and the server chosen among the configured ones (a cluster's nodes). */
    private final NoDelaySocketFactory sockets;
    private final ControlMlManager controlMl;
    private final ScheduledExecutorService connector = Executors.newSingleThreadScheduledExecutor(NamedThreads.daemon(
            "sabot-session-connect"));
    private final ExecutorService notifier = Executors.newSingleThreadExecutor(
            NamedThreads.daemon("sabot-session-events"));
    private final List<SessionListener> listeners = new CopyOnWriteArrayList<>();
    /**
     * The running tasks' references: their services are got only when the identity is published (after a login), never
     * while this component is created, where a task that references {@link RobotSession} (remotefs, portal) would be
     * a circle for SCR.
     */
    private final ServiceTracker<OnboardTask, ServiceReference<OnboardTask>> tasks;
    private final BundleContext context;
    private final LinkWatch linkWatch;
    /** The fleet lobby of {@code controlml.lobby}; empty when none is configured. */
    private final Optional<SessionLobby> lobby;

    private final Object lock = new Object();
    /** Guarded by {@link #lock}: the state listeners were last told. */
    private boolean online;
    /** Guarded by {@link #lock}: a connection attempt is scheduled. */
    private boolean connectPending;
    /** Guarded by {@link #lock}: an identity publication is scheduled. */
    private boolean identityPending;
    /** Guarded by {@link #lock}: an attempt is running (it handles a loss during itself). */
    private boolean attempting;
    /** Guarded by {@link #lock}. */
    private String lastLoss = "not connected yet";
    private volatile boolean stopping;
    /** The account's password: the file's, until an enrolment token in it has been replaced ({@link #replaceToken}). */
    private volatile String password;

    /** Connector thread only: failed attempts since the last login. */
    private int failures;
    /** Connector thread only: the servers not yet tried since the last login or the last round's end. */
    private int untried;
    private volatile long offlineSinceNanos = System.nanoTime();

    private record Announced(PresenceLevel level, String reason) {
    }

    private volatile Announced presence = new Announced(PresenceLevel.FREE, "idle");

    @Activate
    public ControlMlSession(@Reference InventorySource inventorySource, BundleContext context,
            Map<String, Object> properties) {
        this.settings = ControlMlSettings.of(properties);
        this.password = settings.password();
        this.sockets = new NoDelaySocketFactory(settings.servers());
        this.untried = sockets.size();
        this.inventorySource = inventorySource;
        this.version = context.getBundle().getVersion().toString();
        XMPPTCPConnectionConfiguration.Builder config = XMPPTCPConnectionConfiguration.builder();
        try {
            config.setXmppDomain(settings.jid().asDomainBareJid())
                    // the first server's; the sockets connect to the one chosen (NoDelaySocketFactory), a name resolved
                    // when connecting, not here
                    .setHostAddressByNameOrIp(settings.servers().get(0))
                    .setPort(settings.port())
                    .setUsernameAndPassword(settings.jid().getLocalpart(), password)
                    .setResource(settings.resource())
                    .setSocketFactory(sockets)
                    .setConnectTimeout((int) CONNECT_TIMEOUT.toMillis())
                    .setSendPresence(false); // the session sends its own presence, with level and reason
        } catch (org.jxmpp.stringprep.XmppStringprepException e) {
            throw new IllegalArgumentException("resource '" + settings.resource() + "': " + e.getMessage(), e);
        }
        connection = new XMPPTCPConnection(FleetConnections.secured(config, settings.trust()).build());
        connection.setUseStreamManagement(true);
        connection.setUseStreamManagementResumption(true);
        AccessPolicy policy = settings.open() ? AccessPolicy.OPEN : settings.access().on(connection);
        if (!settings.open()) {
            new RoleCensus(Roster.getInstanceFor(connection), policy, settings.jid().toString()).listen();
        }
        SubscriptionGate.onDevice(connection, policy);
        controlMl = ControlMlManager.getInstanceFor(connection);
        controlMl.setAccessPolicy(policy);
        controlMl.setStaleCommandPolicy(StaleCommandPolicy.refuseOlderThan(settings.staleCommandAfter()));
        connection.addConnectionListener(new ConnectionListener() {
            @Override
            public void connectionClosedOnError(Exception e) {
                lost(describe(e));
            }

            @Override
            public void connectionClosed() {
                if (!stopping) {
                    lost("the connection was closed");
                }
            }
        });
        linkWatch = new LinkWatch(connection, settings.liveness(), NamedThreads.daemon("sabot-session-liveness"),
                this::silent);
        lobby = settings.lobby().map(room -> new SessionLobby(connection, room));
        this.context = context;
        tasks = new ServiceTracker<>(context, OnboardTask.class, null) {
            @Override
            public ServiceReference<OnboardTask> addingService(ServiceReference<OnboardTask> reference) {
                scheduleIdentity();
                return reference;
            }

            @Override
            public void removedService(ServiceReference<OnboardTask> reference, ServiceReference<OnboardTask> same) {
                scheduleIdentity();
            }
        };
        tasks.open();
        LOG.info("controlml task started: {} on {}:{} (resource {}, TLS trusting {}), {}{}", settings.jid(),
                String.join(", ", settings.servers()), settings.port(), settings.resource(), settings.trust().describe(),
                settings.open() ? "roles: none, the policy is open" : "roles from the server's groups: " + settings
                        .access().describe(), lobby.map(l -> "; fleet lobby " + l.room()).orElse(""));
        if (settings.open()) {
            LOG.warn("controlml.openPolicy = true: everyone who reaches this robot through its server is its "
                    + "maintainer (goals, gains, limits, files)");
        }
        scheduleConnect(Duration.ZERO);
    }

    @Deactivate
    void deactivate() {
        stopping = true;
        linkWatch.close();
        lobby.ifPresent(SessionLobby::close);
        tasks.close();
        connector.shutdownNow();
        try {
            // an attempt in progress ends within the connect timeout (a blocking socket connect ignores interrupts)
            connector.awaitTermination(CONNECT_TIMEOUT.toMillis() + 1000, TimeUnit.MILLISECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        boolean wasOnline;
        synchronized (lock) {
            wasOnline = online;
            online = false;
        }
        if (connection.isConnected()) {
            try {
                connection.disconnect(connection.getStanzaFactory().buildPresenceStanza().ofType(
                        Presence.Type.unavailable).setStatus("stopped").build());
            } catch (SmackException.NotConnectedException e) {
                connection.instantShutdown();
            }
        }
        if (wasOnline) {
            notify(l -> l.offline("the controlml task stopped"));
        }
        notifier.shutdown();
        try {
            notifier.awaitTermination(5, TimeUnit.SECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        LOG.info("controlml task stopped: {} disconnected", settings.jid());
    }

    // ------------------------------------------------------------------------------------------ connecting

    private void scheduleConnect(Duration delay) {
        synchronized (lock) {
            if (stopping || connectPending) {
                return;
            }
            connectPending = true;
        }
        try {
            connector.schedule(this::attempt, delay.toNanos(), TimeUnit.NANOSECONDS);
        } catch (RejectedExecutionException stopped) {
            // deactivated meanwhile
        }
    }

    /** One connection attempt, on the connector thread. */
    private void attempt() {
        synchronized (lock) {
            connectPending = false;
            if (stopping) {
                return;
            }
            attempting = true;
        }
        boolean nowOnline = false;
        try {
            try {
                if (!connection.isAuthenticated()) {
                    if (connection.isConnected()) {
                        // half made by an attempt that timed out on a silent network: its stream's state would be
                        // taken for this one's (Smack then finds no SASL mechanisms, attempt after attempt)
                        connection.instantShutdown();
                    }
                    connection.connect();
                    connection.login(settings.jid().getLocalpart(), password);
                    if (Enrolment.isToken(password)) {
                        replaceToken();
                    }
                }
            } catch (FleetException e) {
                failed(e.getMessage());
                return;
            } catch (SmackException | XMPPException | java.io.IOException | RuntimeException e) {
                String certificate = settings.trust().explain(e, settings.jid().getDomain().toString());
                failed(certificate != null ? certificate : describe(e));
                return;
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt(); // deactivation
                return;
            }
            boolean retry;
            synchronized (lock) {
                attempting = false;
                // a loss between login and here was left to this attempt by lost()
                nowOnline = connection.isAuthenticated() && !stopping;
                retry = !nowOnline && !stopping;
                if (nowOnline) {
                    online = true;
                    linkWatch.online();
                    notify(SessionListener::online);
                }
            }
            if (retry) {
                failed("the connection was lost right after login");
            }
        } finally {
            synchronized (lock) {
                attempting = false;
            }
        }
        if (!nowOnline) {
            return;
        }
        double offlineFor = (System.nanoTime() - offlineSinceNanos) / 1e9;
        LOG.info("online as {}{}{}", connection.getUser(), sockets.size() > 1 ? " through " + sockets.current() : "",
                failures == 0 ? "" : String.format(" after %d failed attempt(s), %.1f s offline", failures,
                        offlineFor));
        failures = 0;
        untried = sockets.size();
        publishIdentity(); // first: whoever sees the presence finds the vCard already stored
        sendPresence();
        lobby.ifPresent(SessionLobby::loggedIn);
    }

    /**
     * The first login with an enrolment token: the token is replaced with a password of the robot's own, on the
     * server and in the password file, so that the token is good for this one login ({@link Enrolment}). The new
     * password is written beside the file first: a folder this process cannot write stops here, the token still good.
     */
    private void replaceToken() throws FleetException, InterruptedException {
        Path file = settings.passwordFile();
        String own = Enrolment.newPassword();
        Path prepared;
        try {
            prepared = PasswordFile.prepare(file, own);
        } catch (java.io.IOException e) {
            throw new FleetException("cannot write a new password beside " + file + " (" + e + "); the enrolment token"
                    + " is kept until it can", e);
        }
        try {
            Enrolment.replaceToken(connection, own);
        } catch (FleetException e) {
            deleteQuietly(prepared);
            throw e;
        }
        password = own;
        try {
            PasswordFile.commit(prepared, file);
        } catch (java.io.IOException e) {
            LOG.error("the server now knows this robot by a new password, but it could not be put in {} ({}): this "
                    + "session goes on with it, a restart will not log in; the lab enrols the robot again (./sabot enrol"
                    + " refuse {}, then ./sabot enrol token {})", file, e, settings.jid(), settings.jid());
            return;
        }
        LOG.warn("enrolled: the enrolment token in {} is replaced with a password of this robot's own (a robot the lab "
                + "has not approved yet obeys nobody: ./sabot enrol approve {})", file, settings.jid());
    }

    private static void deleteQuietly(Path file) {
        try {
            java.nio.file.Files.deleteIfExists(file);
        } catch (java.io.IOException e) {
            LOG.debug("cannot delete {}: {}", file, e.toString());
        }
    }

    private void failed(String reason) {
        synchronized (lock) {
            lastLoss = reason; // the status says why the session is offline
        }
        failures++;
        String server = sockets.current();
        // another server of the list not tried since the last login: at once; once all were, the back-off
        boolean another = sockets.size() > 1 && untried > 1;
        Duration delay = another ? Duration.ZERO : backoff(failures, settings.reconnectMin(), settings.reconnectMax());
        if (sockets.size() > 1) {
            untried = another ? untried - 1 : sockets.size();
            sockets.next();
        }
        if (failures <= LOGGED_FAILURES) {
            LOG.warn("cannot connect to {}:{} as {} (attempt {}): {}; next attempt{} in {} s{}", server,
                    settings.port(), settings.jid(), failures, reason, sockets.size() > 1 ? " through "
                            + sockets.current() : "", delay.toMillis() / 1000.0,
                    failures == LOGGED_FAILURES ? " (further failures are logged at debug level until the session is"
                            + " back; it keeps trying every " + settings.reconnectMax().toMillis() / 1000.0
                            + " s at most)" : "");
        } else {
            LOG.debug("cannot connect (attempt {}): {}; next attempt in {} s", failures, reason, delay.toMillis()
                    / 1000.0);
        }
        scheduleConnect(delay); // before the shutdown below, whose closed callback would schedule the minimum
        if (connection.isConnected()) {
            connection.instantShutdown(); // e.g. connected but refused at login: start the next attempt afresh
        }
    }

    /** @return the delay after the n-th failure in a row: min, 2 min, 4 min... capped at max */
    static Duration backoff(int failures, Duration min, Duration max) {
        long nanos = min.toNanos();
        for (int i = 1; i < failures && nanos < max.toNanos(); i++) {
            nanos *= 2;
        }
        return Duration.ofNanos(Math.min(nanos, max.toNanos()));
    }

    /**
     * The link went silent ({@link LinkWatch}): nothing closed it, nothing passes. Taken as a loss, and the connection
     * is dropped so that the session reconnects (with back-off, as after any loss).
     */
    private void silent(String reason) {
        lost(reason);
        sockets.abandonLast(); // no TLS close: it would reach the server after a resumption and end that stream
        connection.instantShutdown();
    }

    /** The connection was lost (Smack's reader or writer thread, or a silent link). */
    private void lost(String reason) {
        synchronized (lock) {
            if (stopping) {
                return;
            }
            lastLoss = reason;
            if (online) {
                online = false;
                offlineSinceNanos = System.nanoTime();
                lobby.ifPresent(SessionLobby::lost);
                LOG.warn("offline: {}; reconnecting in {} s", reason, settings.reconnectMin().toMillis() / 1000.0);
                notify(l -> l.offline(reason));
            }
            if (attempting) {
                return; // the attempt in progress schedules the next one
            }
        }
        scheduleConnect(settings.reconnectMin());
    }

    /** @return one line for a log, the status and a fault's reason (a stream error: its condition and text) */
    private static String describe(Throwable e) {
        if (e instanceof XMPPException.StreamErrorException s) {
            String text = s.getStreamError().getDescriptiveText();
            return "stream error " + s.getStreamError().getCondition() + (text == null ? "" : " (" + text + ")");
        }
        String message = e.getMessage();
        return e.getClass().getSimpleName() + (message == null || message.isBlank() ? "" : ": " + message.strip()
                .replaceAll("\\s+", " "));
    }

    /** Queues a notification; call with {@link #lock} held so that notifications keep the order of the changes. */
    private void notify(java.util.function.Consumer<SessionListener> event) {
        for (SessionListener l : listeners) {
            try {
                notifier.execute(() -> {
                    try {
                        event.accept(l);
                    } catch (RuntimeException e) {
                        LOG.warn("session listener {} failed", l, e);
                    }
                });
            } catch (RejectedExecutionException stopped) {
                return;
            }
        }
    }

    // ------------------------------------------------------------------------------------------ announcing

    private void sendPresence() {
        Announced p = presence;
        try {
            connection.sendStanza(connection.getStanzaFactory().buildPresenceStanza().ofType(Presence.Type.available)
                    .setMode(p.level().mode()).setStatus(p.reason()).build());
        } catch (SmackException.NotConnectedException e) {
            LOG.debug("presence not sent (offline); sent again at the next login");
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    private void scheduleIdentity() {
        synchronized (lock) {
            if (!online || identityPending || stopping) {
                return; // published anyway at the next login
            }
            identityPending = true;
        }
        try {
            connector.schedule(() -> {
                synchronized (lock) {
                    identityPending = false;
                }
                if (isOnline()) {
                    publishIdentity();
                }
            }, IDENTITY_SETTLE.toNanos(), TimeUnit.NANOSECONDS);
        } catch (RejectedExecutionException stopped) {
            // deactivated meanwhile
        }
    }

    private void publishIdentity() {
        Map<String, String> running = runningTasks();
        IdentityResult<QrInventory.Encoded> result;
        try {
            result = DeviceIdentityManager.getInstanceFor(connection).publish(OnboardIdentity.profile(settings, version,
                    running, vCardPage()), OnboardIdentity.inventory(inventorySource, settings, running));
        } catch (RuntimeException e) {
            LOG.warn("vCard identity not published: {}", describe(e));
            return;
        }
        if (result instanceof IdentityResult.Err<QrInventory.Encoded> err) {
            if (stopping) {
                return; // interrupted by deactivation
            }
            LOG.warn("vCard identity not published: {} ({})", err.text(), err.problem());
        } else {
            QrInventory.Encoded qr = result.orElseThrow();
            LOG.info("vCard identity published: {} task(s), inventory of {} bytes as a {} QR code", running.size(),
                    qr.xmlBytes(), qr.form());
        }
    }

    /** @return the running tasks' names and their bundles' versions, sorted by name */
    private Map<String, String> runningTasks() {
        Map<String, String> running = new TreeMap<>();
        eachTask((ref, task) -> {
            if (ref.getBundle() != null) {
                running.put(task.name(), ref.getBundle().getVersion().toString());
            }
        });
        return running;
    }

    /** @return the first running task's web page (by task name), the vCard's URL; null when none serves one */
    private java.net.URI vCardPage() {
        java.util.SortedMap<String, java.net.URI> pages = new TreeMap<>();
        eachTask((ref, task) -> task.page().ifPresent(uri -> pages.put(task.name(), uri)));
        return pages.isEmpty() ? null : pages.get(pages.firstKey());
    }

    private void eachTask(java.util.function.BiConsumer<ServiceReference<OnboardTask>, OnboardTask> action) {
        ServiceReference<OnboardTask>[] refs = tasks.getServiceReferences();
        if (refs == null) {
            return;
        }
        for (ServiceReference<OnboardTask> ref : refs) {
            OnboardTask task;
            try {
                task = context.getService(ref);
            } catch (IllegalStateException stopped) {
                return; // deactivated meanwhile
            }
            if (task != null) {
                try {
                    action.accept(ref, task);
                } finally {
                    context.ungetService(ref);
                }
            }
        }
    }

    // ------------------------------------------------------------------------------------------ RobotSession

    @Override
    public String jid() {
        return settings.jid().toString();
    }

    @Override
    public XMPPConnection connection() {
        return connection;
    }

    @Override
    public ControlMlManager controlMl() {
        return controlMl;
    }

    @Override
    public boolean isOnline() {
        synchronized (lock) {
            return online;
        }
    }

    @Override
    public List<String> lobbyMembers() {
        return lobby.map(SessionLobby::members).orElse(List.of());
    }

    @Override
    public void setPresence(PresenceLevel level, String reason) {
        presence = new Announced(java.util.Objects.requireNonNull(level, "level"), reason == null ? "" : reason);
        if (isOnline()) {
            try {
                connector.execute(this::sendPresence); // never on the caller's thread: it may be the control loop
            } catch (RejectedExecutionException stopped) {
                // deactivated meanwhile
            }
        }
    }

    @Override
    public void addListener(SessionListener listener) {
        synchronized (lock) {
            listeners.add(listener);
            if (online) {
                try {
                    notifier.execute(listener::online);
                } catch (RejectedExecutionException stopped) {
                    // deactivated meanwhile
                }
            }
        }
    }

    @Override
    public void removeListener(SessionListener listener) {
        listeners.remove(listener);
    }

    // ------------------------------------------------------------------------------------------ OnboardTask

    @Override
    public PresenceLevel presenceLevel() {
        return presence.level();
    }

    @Override
    public String presenceReason() {
        return presence.reason();
    }

    @Override
    public boolean checkPassword(String account, String password) throws IOException {
        org.jxmpp.jid.EntityBareJid jid;
        try {
            jid = org.jxmpp.jid.impl.JidCreate.entityBareFrom(account);
        } catch (org.jxmpp.stringprep.XmppStringprepException | RuntimeException e) {
            return false;
        }
        if (!jid.asDomainBareJid().equals(settings.jid().asDomainBareJid()) || password.isEmpty()) {
            return false; // only the robot's server knows its accounts' passwords
        }
        XMPPTCPConnectionConfiguration.Builder config = XMPPTCPConnectionConfiguration.builder();
        config.setXmppDomain(jid.asDomainBareJid())
                .setHostAddressByNameOrIp(settings.servers().get(0))
                .setPort(settings.port())
                .setUsernameAndPassword(jid.getLocalpart(), password)
                .setSocketFactory(new NoDelaySocketFactory(settings.servers()))
                .setConnectTimeout((int) CONNECT_TIMEOUT.toMillis())
                .setSendPresence(false);
        XMPPTCPConnection check = new XMPPTCPConnection(FleetConnections.secured(config, settings.trust()).build());
        Roster.getInstanceFor(check).setRosterLoadedAtLogin(false);
        try {
            check.connect();
            check.login();
            return true;
        } catch (org.jivesoftware.smack.sasl.SASLErrorException refused) {
            return false;
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IOException("interrupted while checking the password of " + jid, e);
        } catch (SmackException | XMPPException e) {
            throw new IOException("the XMPP server did not check the password of " + jid + ": " + describe(e), e);
        } finally {
            check.disconnect();
        }
    }

    @Override
    public String name() {
        return ControlMlSettings.TASK;
    }

    @Override
    public String status() {
        synchronized (lock) {
            return online ? "online as " + connection.getUser() : "offline (" + lastLoss + "), reconnecting";
        }
    }
}
