package sabot.workbench.controlml.internal;

import java.io.IOException;
import java.net.InetAddress;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Clock;
import java.time.Duration;
import java.time.Instant;
import java.util.ArrayList;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ConcurrentSkipListMap;
import java.util.concurrent.CopyOnWriteArraySet;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.function.UnaryOperator;

import org.eclipse.core.runtime.preferences.IEclipsePreferences;
import org.eclipse.core.runtime.preferences.IEclipsePreferences.IPreferenceChangeListener;
import org.jivesoftware.smack.ConnectionConfiguration.SecurityMode;
import org.jivesoftware.smack.ConnectionListener;
import org.jivesoftware.smack.ReconnectionManager;
import org.jivesoftware.smack.SmackException;
import org.jivesoftware.smack.XMPPException;
import org.jivesoftware.smack.packet.StanzaError;
import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.RosterEntry;
import org.jivesoftware.smack.roster.RosterGroup;
import org.jivesoftware.smack.roster.RosterListener;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jivesoftware.smackx.muc.MultiUserChatManager;
import org.jivesoftware.smackx.vcardtemp.VCardManager;
import org.jivesoftware.smackx.vcardtemp.packet.VCard;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;
import org.jxmpp.stringprep.XmppStringprepException;
import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.Deactivate;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlError;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.PresenceLevel;
import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.payload.FileChunk;
import sabot.controlml.payload.FileQuery;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.GridMap;
import sabot.controlml.payload.MissionState;
import sabot.controlml.payload.MissionStatus;
import sabot.controlml.payload.NoQuery;
import sabot.controlml.payload.TrajectoryPayload;
import sabot.controlml.payload.VelocityCommand;
import sabot.fleet.FleetConnections;
import sabot.fleet.FleetException;
import sabot.fleet.FleetLobby;
import sabot.fleet.RosterCompiler;
import sabot.fleet.PresenceLevels;
import sabot.fleet.SubscriptionGate;
import sabot.identity.DeviceIdentityManager;
import sabot.identity.DeviceProfile;
import sabot.identity.DeviceVCards;
import sabot.identity.IdentityResult;
import sabot.model.geometry.Twist2D;
import sabot.model.map.MapServerFormat;
import sabot.model.map.OccupancyGrid;
import sabot.workbench.account.XmppAccount;
import sabot.workbench.account.XmppAccountStore;
import sabot.workbench.fleet.Availability;
import sabot.workbench.fleet.ConnectionStatus;
import sabot.workbench.fleet.ConnectionStatus.State;
import sabot.workbench.fleet.FleetCommandException;
import sabot.workbench.fleet.FleetListener;
import sabot.workbench.fleet.FleetState;
import sabot.workbench.fleet.RobotIdentity;
import sabot.workbench.fleet.RobotState;

/**
 * The faceless ControlML plug-in: the workbench's one XMPP connection (the account of the preferences), the robots of
 * its roster, their presence levels and telemetry, published as {@link FleetState}.
 * <p>
 * Threads: one connection thread (connect, log in, follow robots, back-off), a small pool for requests (each waits
 * for its robot's answer), and one notification thread that calls the listeners in order. Smack's threads only
 * update the state and queue notifications. All of them run at {@link #BACKGROUND_PRIORITY}.
 */
@Component(service = FleetState.class, immediate = true)
public final class ControlMlFleet implements FleetState {

    /** Roster group of the robots the workbench follows (fleet rule 12 puts configured robots there). */
    public static final String ROBOTS_GROUP = "Sabot robots";
    /** Resource part of the workbench's full JID (several workbenches of one operator differ by a suffix). */
    static final String RESOURCE_PREFIX = "workbench-";
    /** The telemetry every followed robot is subscribed to (docs/CONTROLML.md section 6). */
    static final List<Resource<?, ?>> TELEMETRY = List.of(Resources.POSITION, Resources.VELOCITY, Resources.MISSION,
            Resources.OBSTACLES);

    /**
     * Priority of every thread of the connection, its own and Smack's: below the UI thread's, so that a frame need not
     * wait for telemetry ingest on a busy core. Linux applies it as the nice value the product's start script sets
     * (SABOT_WORKBENCH_BACKGROUND_NICE, default 10, docs/WORKBENCH.md); without the script's JVM options (0, or the
     * UI tests' runtime) HotSpot only records Java priorities. An ingest that falls behind shows: late poses grey
     * their robot (RobotState.isLate).
     */
    static final int BACKGROUND_PRIORITY = Thread.MIN_PRIORITY;

    private static final Logger LOG = LoggerFactory.getLogger("sabot.workbench.controlml");

    private final Clock clock;
    private final Backoff backoff;
    private final Duration requestTimeout;
    private final ScheduledExecutorService connector = Executors.newSingleThreadScheduledExecutor(named(
            "sabot-fleet-connection"));
    private final ExecutorService requests = Executors.newFixedThreadPool(4, named("sabot-fleet-request"));
    private final ExecutorService notifier = Executors.newSingleThreadExecutor(named("sabot-fleet-events"));
    private final Map<String, RobotState> robots = new ConcurrentSkipListMap<>();
    private final Set<FleetListener> listeners = new CopyOnWriteArraySet<>();
    private final Map<String, CompletableFuture<GridMap>> maps = new ConcurrentHashMap<>();
    private final Object stateLock = new Object();
    /** True while a reconnection is queued: the several keys of one account change make one reconnection. */
    private final java.util.concurrent.atomic.AtomicBoolean reconnectQueued =
            new java.util.concurrent.atomic.AtomicBoolean();
    private final IPreferenceChangeListener accountChanged = e -> {
        if (e.getKey().startsWith(XmppAccountStore.KEY_PREFIX)) {
            reconnect();
        }
    };
    /**
     * How often the robots' roster state is checked again while online: a subscription handshake cut short (the
     * workbench reconnected in between) is asked for again, and a presence missed is read from the roster.
     */
    static final long RECONCILE_MS = 2000;

    private volatile ConnectionStatus status;
    /** The live connection, touched on the connection thread only (read elsewhere). */
    private volatile Session session;
    private IEclipsePreferences node;

    /** The connection of one login and what hangs on it. */
    private record Session(XMPPTCPConnection connection, ControlMlManager manager, Roster roster, long generation) {
    }

    private final AtomicInteger generation = new AtomicInteger();

    public ControlMlFleet() {
        this(Clock.systemUTC(), new Backoff(Duration.ofMillis(500), Duration.ofSeconds(30)), Duration.ofSeconds(10));
    }

    ControlMlFleet(Clock clock, Backoff backoff, Duration requestTimeout) {
        this.clock = clock;
        this.backoff = backoff;
        this.requestTimeout = requestTimeout;
        this.status = new ConnectionStatus(State.CONNECTING, "", "", clock.instant());
    }

    @Activate
    void activate() {
        // vcard-temp parsed with the device fields (GEO, FN, ROLE) that Smack's own provider drops
        DeviceIdentityManager.registerProvider();
        node = XmppAccountStore.workbenchNode();
        node.addPreferenceChangeListener(accountChanged);
        connector.execute(this::connect);
        LOG.info("ControlML plug-in started");
    }

    @Deactivate
    void deactivate() {
        if (node != null) {
            node.removePreferenceChangeListener(accountChanged);
        }
        connector.execute(() -> {
            closeSession();
            setStatus(State.STOPPED, status.account(), "");
        });
        connector.shutdown();
        try {
            connector.awaitTermination(10, TimeUnit.SECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        requests.shutdownNow();
        notifier.shutdown();
        LOG.info("ControlML plug-in stopped");
    }

    // ------------------------------------------------------------------------------------------------ FleetState

    @Override
    public ConnectionStatus connection() {
        return status;
    }

    @Override
    public List<RobotState> robots() {
        return List.copyOf(robots.values());
    }

    @Override
    public Optional<RobotState> robot(String jid) {
        return Optional.ofNullable(robots.get(jid));
    }

    @Override
    public void addListener(FleetListener listener) {
        // queued on the notification thread: the listener sees the present state first, then every later change
        notifier.execute(() -> {
            if (listeners.add(listener)) {
                listener.connectionChanged(status);
                robots.values().forEach(listener::robotChanged);
            }
        });
    }

    @Override
    public void removeListener(FleetListener listener) {
        listeners.remove(listener);
    }

    @Override
    public void reconnect() {
        if (!connector.isShutdown() && reconnectQueued.compareAndSet(false, true)) {
            connector.execute(() -> {
                reconnectQueued.set(false);
                backoff.reset();
                closeSession();
                connect();
            });
        }
    }

    @Override
    public CompletableFuture<Void> goTo(String robot, Goal goal) {
        CompletableFuture<Void> sent = this.<Goal>set(robot, Resources.GOAL, goal).thenApply(readBack -> null);
        // the plan exists once the robot took the goal; show it with the goal
        sent.thenRun(() -> fetchPlan(robot));
        return sent;
    }

    @Override
    public CompletableFuture<Void> stop(String robot) {
        RobotState r = robots.get(robot);
        MissionStatus m = r == null ? null : r.mission();
        if (m != null && m.state().isActive()) {
            // the robot's own maintenance flag, so that the command is read as a transition, not a mode switch
            return set(robot, Resources.MISSION, new MissionStatus(MissionState.ABORTED, m.maintenance(), m.progress(),
                    "stopped by the operator")).thenApply(x -> null);
        }
        return drive(robot, Twist2D.ZERO);
    }

    @Override
    public CompletableFuture<Void> drive(String robot, Twist2D twist) {
        return set(robot, Resources.VELOCITY, new VelocityCommand(clock.instant(), twist)).thenApply(x -> null);
    }

    /**
     * Where a robot keeps its map for workbenches when {@code cm.map} cannot carry it (a payload holds at most 64 KiB
     * of characters, about 30,000 cells: the lab's 240 x 180 grid does not fit): a ROS map_server YAML at the root
     * of its remote files, its image beside it.
     */
    public static final String MAP_FILE = "map.yaml";

    @Override
    public CompletableFuture<GridMap> map(String robot) {
        CompletableFuture<GridMap> f = maps.computeIfAbsent(robot, r -> this.<GridMap>get(r, Resources.MAP)
                .exceptionallyCompose(e -> {
                    FleetCommandException refused = FleetCommandException.in(e);
                    return refused != null && refused.condition() == ControlMlCondition.PAYLOAD_TOO_LARGE
                            ? mapFromFiles(r) : CompletableFuture.failedFuture(e);
                }));
        // a failed fetch is not cached: the next call asks again
        f.whenComplete((m, e) -> {
            if (e != null) {
                maps.remove(robot, f);
            }
        });
        return f;
    }

    /** The map from the robot's remote files ({@link #MAP_FILE} and the image it names), on the request pool. */
    private CompletableFuture<GridMap> mapFromFiles(String robot) {
        return CompletableFuture.supplyAsync(() -> {
            Path dir = null;
            try {
                dir = Files.createTempDirectory("sabot-map-");
                Path yaml = dir.resolve(MAP_FILE);
                Files.write(yaml, download(robot, MAP_FILE));
                String image = MapServerFormat.readMetadata(yaml).image();
                if (image.contains("/") || image.startsWith(".")) {
                    throw new FleetCommandException(ControlMlCondition.INVALID_VALUE, robot + "'s " + MAP_FILE
                            + " names an image outside its folder: " + image);
                }
                Files.write(dir.resolve(image), download(robot, image));
                MapServerFormat.LoadedMap loaded = MapServerFormat.load(yaml);
                OccupancyGrid g = loaded.grid();
                return new GridMap(g.resolution(), g.width(), g.height(), g.geometry().origin(), g.toArray());
            } catch (IOException e) {
                throw new FleetCommandException(ControlMlCondition.INVALID_VALUE, "map of " + robot + " from its "
                        + "files: " + e.getMessage());
            } finally {
                deleteTree(dir);
            }
        }, requests);
    }

    /** Reads a whole file of the robot's remote files, chunk by chunk (each checked by its SHA-256 on arrival). */
    private byte[] download(String robot, String path) {
        java.io.ByteArrayOutputStream out = new java.io.ByteArrayOutputStream();
        while (true) {
            FileQuery q = new FileQuery(path, out.size(), 0);
            FileChunk c = callNow(robot, (m, jid) -> m.get(jid, Resources.FS_READ, q));
            out.writeBytes(c.data());
            if (c.last()) {
                return out.toByteArray();
            }
            if (c.data().length == 0) {
                throw new FleetCommandException(ControlMlCondition.DEVICE_FAULT, robot + " sent an empty chunk of "
                        + path + " at " + out.size());
            }
        }
    }

    private static void deleteTree(Path dir) {
        if (dir == null) {
            return;
        }
        try (var files = Files.list(dir)) {
            for (Path f : (Iterable<Path>) files::iterator) {
                Files.deleteIfExists(f);
            }
            Files.deleteIfExists(dir);
        } catch (IOException e) {
            LOG.debug("cannot remove {}: {}", dir, e.getMessage());
        }
    }

    @Override
    public <T> CompletableFuture<T> get(String robot, Resource<T, NoQuery> resource) {
        return request(robot, (m, jid) -> m.get(jid, resource));
    }

    @Override
    public <T, Q> CompletableFuture<T> get(String robot, Resource<T, Q> resource, Q query) {
        return request(robot, (m, jid) -> m.get(jid, resource, query));
    }

    @Override
    public <T> CompletableFuture<T> set(String robot, Resource<T, ?> resource, T value) {
        return request(robot, (m, jid) -> m.set(jid, resource, value));
    }

    /**
     * The robot's vCard (vcard-temp, stored by the server, so it is read while the robot is offline too), parsed with
     * {@code sabot.identity}'s device profile, on the request pool.
     */
    @Override
    public CompletableFuture<RobotIdentity> identity(String robot) {
        return onRequestPool(() -> fetchIdentity(robot));
    }

    /** @return the session to ask {@code robot} through; throws why it cannot be asked (NOT_CONNECTED) */
    private Session sessionFor(String robot) {
        Session s = session;
        if (s == null || !s.connection().isAuthenticated()) {
            throw new FleetCommandException(ControlMlCondition.NOT_CONNECTED, "the workbench is not connected ("
                    + status.summary() + ")");
        }
        if (!robots.containsKey(robot)) {
            throw new FleetCommandException(ControlMlCondition.NOT_CONNECTED, robot
                    + " is not a robot of this workbench's fleet");
        }
        return s;
    }

    /** Request pool: loads and parses the vCard; each failure as a {@link FleetCommandException} for the operator. */
    private RobotIdentity fetchIdentity(String robot) {
        Session s = sessionFor(robot);
        VCard card;
        try {
            card = VCardManager.getInstanceFor(s.connection()).loadVCard(JidCreate.entityBareFrom(robot));
        } catch (XmppStringprepException e) {
            throw new FleetCommandException(ControlMlCondition.INVALID_VALUE, "'" + robot + "' is not a JID: " + e
                    .getMessage());
        } catch (XMPPException.XMPPErrorException e) {
            StanzaError.Condition c = e.getStanzaError().getCondition();
            if (c == StanzaError.Condition.item_not_found || c == StanzaError.Condition.service_unavailable) {
                throw new FleetCommandException(ControlMlCondition.UNKNOWN_RESOURCE, robot + " has no vCard");
            }
            throw new FleetCommandException(ControlMlCondition.UNSPECIFIED, "vCard of " + robot + ": " + c);
        } catch (SmackException.NoResponseException e) {
            throw new FleetCommandException(ControlMlCondition.TIMEOUT, "no vCard of " + robot + " within "
                    + s.connection().getReplyTimeout() + " ms");
        } catch (SmackException e) {
            throw new FleetCommandException(ControlMlCondition.NOT_CONNECTED, "vCard of " + robot + ": " + e);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new FleetCommandException(ControlMlCondition.UNSPECIFIED, "vCard of " + robot + ": interrupted");
        }
        IdentityResult<DeviceProfile> parsed = DeviceVCards.profileOf(card);
        if (parsed instanceof IdentityResult.Err<DeviceProfile> e) {
            ControlMlCondition c = e.problem() == IdentityResult.Problem.NO_VCARD ? ControlMlCondition.UNKNOWN_RESOURCE
                    : ControlMlCondition.INVALID_VALUE;
            throw new FleetCommandException(c, robot + "'s vCard: " + e.text());
        }
        DeviceProfile p = parsed.orElseThrow();
        return new RobotIdentity(p.jid(), p.nickname(), p.portal() == null ? null : p.portal().toString(), p
                .latitude(), p.longitude(), p.uid(), p.category(), p.manufacturer(), p.model(), card.getAvatar());
    }

    @FunctionalInterface
    private interface Call<T> {
        Outcome<T> on(ControlMlManager manager, Jid robot);
    }

    /** Runs a request on the request pool. */
    private <T> CompletableFuture<T> request(String robot, Call<T> call) {
        return onRequestPool(() -> callNow(robot, call));
    }

    /**
     * Runs work on the request pool; the future fails with a {@link FleetCommandException} (the robot's condition and
     * text, or why it could not be asked), any other failure as UNSPECIFIED.
     */
    private <T> CompletableFuture<T> onRequestPool(java.util.function.Supplier<T> work) {
        CompletableFuture<T> f = new CompletableFuture<>();
        try {
            requests.execute(() -> {
                try {
                    f.complete(work.get());
                } catch (FleetCommandException e) {
                    f.completeExceptionally(e);
                } catch (RuntimeException e) {
                    f.completeExceptionally(new FleetCommandException(ControlMlCondition.UNSPECIFIED, e.toString()));
                }
            });
        } catch (java.util.concurrent.RejectedExecutionException stopped) {
            f.completeExceptionally(new FleetCommandException(ControlMlCondition.NOT_CONNECTED,
                    "the ControlML plug-in has stopped"));
        }
        return f;
    }

    /**
     * Sends a request to the robot's available full JID and waits for the answer (calling thread).
     *
     * @throws FleetCommandException with the robot's condition and text, or why it could not be asked
     */
    private <T> T callNow(String robot, Call<T> call) {
        Session s = sessionFor(robot);
        Presence p;
        try {
            p = s.roster().getPresence(JidCreate.entityBareFrom(robot));
        } catch (XmppStringprepException e) {
            throw new FleetCommandException(ControlMlCondition.INVALID_VALUE, "'" + robot + "' is not a JID: " + e
                    .getMessage());
        }
        if (!p.isAvailable()) {
            throw new FleetCommandException(ControlMlCondition.NOT_CONNECTED, robot + " is offline");
        }
        Outcome<T> o = call.on(s.manager(), p.getFrom());
        if (o instanceof Outcome.Failure<T> failure) {
            ControlMlError e = failure.error();
            throw new FleetCommandException(e.cmCondition() != null ? e.cmCondition() : ControlMlCondition.UNSPECIFIED,
                    e.text() == null ? String.valueOf(e.condition()) : e.text());
        }
        return o.orElseThrow();
    }

    // ------------------------------------------------------------------------------------------------ connection

    /** Connection thread: connects with the stored account, or schedules the next attempt. */
    private void connect() {
        closeSession();
        XmppAccountStore store = XmppAccountStore.workbenchStore();
        XmppAccount account = store.load();
        String problem = account.problem();
        char[] password;
        try {
            password = store.loadPassword();
        } catch (IOException e) {
            setStatus(State.NO_ACCOUNT, account.jid(), e.getMessage());
            return;
        }
        if (problem != null || password == null) {
            // without an account there is no fleet: the robots of a former account go
            new ArrayList<>(robots.keySet()).forEach(this::remove);
            setStatus(State.NO_ACCOUNT, account.jid(), problem != null ? problem : "no password stored");
            return;
        }
        setStatus(State.CONNECTING, account.jid(), account.server() + ":" + account.port());
        XMPPTCPConnection c = null;
        try {
            EntityBareJid me = JidCreate.entityBareFrom(account.jid());
            c = new XMPPTCPConnection(FleetConnections.builder(me.getDomain().toString(), InetAddress.getByName(
                    account.server()), account.port(), securityFor(account.server())).setUsernameAndPassword(me
                            .getLocalpart().toString(), new String(password)).setResource(RESOURCE_PREFIX + Long
                                    .toHexString(System.nanoTime() & 0xffffff)).build());
            ReconnectionManager.getInstanceFor(c).disableAutomaticReconnection(); // our own back-off, below
            ControlMlManager manager = ControlMlManager.getInstanceFor(c);
            manager.setRequestTimeout(requestTimeout);
            Roster roster = Roster.getInstanceFor(c);
            // One roster request at login, ours (reloadAndWait below). Smack would send another when authenticated:
            // the two results come back as asynchronous callbacks, and the later one, computed before a removal
            // whose push was handled in between, brought the removed robot back for good (LiveFleetUiTest's lobby
            // test, seen in CI and under load).
            roster.setRosterLoadedAtLogin(false);
            Session s = new Session(c, manager, roster, generation.incrementAndGet());
            listenTelemetry(s);  // before login: +notify goes into the first presence's entity caps
            SubscriptionGate.onWorkbench(c);
            roster.addRosterListener(new FleetRosterListener(s));
            c.addConnectionListener(new ConnectionListener() {
                @Override
                public void connectionClosedOnError(Exception e) {
                    connector.execute(() -> lost(s, e));
                }
            });
            c.connect().login();
            roster.reloadAndWait(); // the robots are known before the status says online
            session = s;
            for (String r : store.loadRobots()) {
                EntityBareJid jid = JidCreate.entityBareFrom(r);
                if (roster.getEntry(jid) == null) {
                    roster.createItemAndRequestSubscription(jid, jid.getLocalpart().toString(), new String[] {
                            ROBOTS_GROUP });
                }
            }
            refreshRoster(s);
            String lobby = store.loadLobby();
            if (!lobby.isEmpty()) {
                joinLobby(s, lobby);
            }
            backoff.reset();
            setStatus(State.ONLINE, account.jid(), account.server() + ":" + account.port());
            LOG.info("connected as {} to {}:{}; following {} robot(s)", c.getUser(), account.server(), account
                    .port(), robots.size());
            for (RobotState r : robots.values()) {
                if (r.availability() != Availability.OFFLINE) {
                    follow(s, r.jid(), 0);
                }
            }
            connector.schedule(() -> reconcile(s), RECONCILE_MS, TimeUnit.MILLISECONDS);
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
            session = null;
            retry(account.jid(), describe(e));
        }
    }

    private void lost(Session s, Exception e) {
        if (session != s) {
            return; // an older connection's last words
        }
        closeSession();
        retry(status.account(), "connection lost: " + describe(e));
    }

    private void retry(String account, String why) {
        Duration wait = backoff.next();
        setStatus(State.RETRYING, account, why + "; next attempt in " + wait.toMillis() / 1000.0 + " s");
        LOG.warn("XMPP connection of {}: {}; next attempt in {} ms", account, why, wait.toMillis());
        connector.schedule(this::connect, wait.toMillis(), TimeUnit.MILLISECONDS);
    }

    private void closeSession() {
        Session s = session;
        session = null;
        maps.clear();
        if (s != null) {
            s.connection().instantShutdown();
        }
        // nothing is known of the robots without a connection: they stay listed, offline
        for (String jid : robots.keySet()) {
            update(jid, r -> r.withPresence(Availability.OFFLINE, ""));
        }
    }

    static SecurityMode securityFor(String server) {
        // as the robot's session: plain TCP only to a server on this machine, TLS required elsewhere
        boolean loopback = server.equals("localhost") || server.startsWith("127.") || server.equals("::1")
                || server.equals("[::1]");
        return loopback ? SecurityMode.disabled : SecurityMode.required;
    }

    private static String describe(Throwable e) {
        String m = e.getMessage();
        return e.getClass().getSimpleName() + (m == null ? "" : ": " + m);
    }

    // ------------------------------------------------------------------------------------------------ roster

    /** The robots: the roster's entries in {@link #ROBOTS_GROUP}. */
    private void refreshRoster(Session s) {
        Set<String> now = new LinkedHashSet<>();
        RosterGroup group = s.roster().getGroup(ROBOTS_GROUP);
        if (group != null) {
            for (RosterEntry e : group.getEntries()) {
                String jid = e.getJid().toString();
                now.add(jid);
                String name = e.getName() != null && !e.getName().isBlank() ? e.getName() : e.getJid().getLocalpartOrNull()
                        == null ? jid : e.getJid().getLocalpartOrNull().toString();
                if (!robots.containsKey(jid)) {
                    add(jid, name);
                } else if (!robots.get(jid).name().equals(name)) {
                    update(jid, r -> r.withName(name));
                }
                presence(s, s.roster().getPresence(e.getJid()));
            }
        }
        for (String jid : new ArrayList<>(robots.keySet())) {
            if (!now.contains(jid)) {
                remove(jid);
            }
        }
    }

    /** The vCard ROLE of the devices roster rule 11 follows (docs/IDENTITY.md; the onboard product publishes it). */
    static final String ROBOT_ROLE = "robot";

    /**
     * Connection thread: roster rule 11. Joins the fleet lobby (a XEP-0045 room every online device joins) and
     * subscribes to the occupants whose vCard says they are robots ({@link #ROBOT_ROLE}), now and whenever an occupant
     * comes in. A lobby that cannot be joined leaves the workbench with its roster (rule 12); the reason is logged and
     * shown in the status line's detail.
     */
    private void joinLobby(Session s, String room) {
        try {
            EntityBareJid jid = JidCreate.entityBareFrom(room);
            FleetLobby lobby = new FleetLobby(s.connection(), jid);
            lobby.join();
            MultiUserChatManager.getInstanceFor(s.connection()).getMultiUserChat(jid).addParticipantListener(p -> {
                if (p.isAvailable()) {
                    connector.execute(() -> compileRoster(s, lobby));
                }
            });
            LOG.info("joined the fleet lobby {}", room);
            compileRoster(s, lobby);
        } catch (FleetException | XmppStringprepException e) {
            LOG.warn("fleet lobby {}: {}", room, e.getMessage());
        }
    }

    /** Connection thread: subscribes to the lobby's robots not yet in the roster (they then join the fleet). */
    private void compileRoster(Session s, FleetLobby lobby) {
        if (session != s) {
            return;
        }
        try {
            RosterCompiler.Report report = new RosterCompiler(s.connection(), lobby, new RosterCompiler.Rules(
                    p -> ROBOT_ROLE.equals(p.role()), Set.of(), ROBOTS_GROUP)).compile();
            if (!report.subscribed().isEmpty()) {
                LOG.info("fleet lobby: subscribed to {}", report.subscribed());
            }
            report.rejected().forEach((jid, why) -> LOG.debug("fleet lobby: {} not followed: {}", jid, why));
        } catch (FleetException e) {
            LOG.warn("fleet lobby: {}", e.getMessage());
        }
    }

    /** Connection thread, every {@link #RECONCILE_MS} while the session lives: see there. */
    private void reconcile(Session s) {
        if (session != s) {
            return;
        }
        for (RobotState r : robots.values()) {
            try {
                EntityBareJid jid = JidCreate.entityBareFrom(r.jid());
                RosterEntry e = s.roster().getEntry(jid);
                if (e != null && !e.canSeeHisPresence() && !e.isSubscriptionPending()) {
                    LOG.info("asking {} again for its presence (subscription {})", jid, e.getType());
                    s.roster().sendSubscriptionRequest(jid);
                }
                presence(s, s.roster().getPresence(jid));
            } catch (Exception e) {
                LOG.debug("reconciling {}: {}", r.jid(), e.toString());
            }
        }
        connector.schedule(() -> reconcile(s), RECONCILE_MS, TimeUnit.MILLISECONDS);
    }

    private void presence(Session s, Presence p) {
        String jid = p.getFrom().asBareJid().toString();
        if (!robots.containsKey(jid)) {
            return;
        }
        PresenceLevel level = PresenceLevels.of(p);
        Availability a = level == null ? Availability.OFFLINE : switch (level) {
            case FREE -> Availability.FREE;
            case BUSY -> Availability.BUSY;
            case AWAY -> Availability.AWAY;
        };
        String reason = p.getStatus() == null ? "" : p.getStatus();
        RobotState before = robots.get(jid);
        if (before != null && before.availability() == a && before.reason().equals(reason)) {
            return;
        }
        update(jid, r -> r.withPresence(a, reason));
        if (before != null && before.availability() == Availability.OFFLINE && a != Availability.OFFLINE && session
                == s) {
            connector.execute(() -> follow(s, jid, 0));
        }
    }

    private final class FleetRosterListener implements RosterListener {
        private final Session s;

        FleetRosterListener(Session s) {
            this.s = s;
        }

        @Override
        public void entriesAdded(java.util.Collection<Jid> addresses) {
            changed();
        }

        @Override
        public void entriesUpdated(java.util.Collection<Jid> addresses) {
            changed();
        }

        @Override
        public void entriesDeleted(java.util.Collection<Jid> addresses) {
            changed();
        }

        private void changed() {
            connector.execute(() -> {
                if (session == s) {
                    refreshRoster(s);
                }
            });
        }

        @Override
        public void presenceChanged(Presence presence) {
            if (session == s || session == null) {
                presence(s, presence);
            }
        }
    }

    // ------------------------------------------------------------------------------------------------ telemetry

    /** Most attempts to follow a robot whose nodes do not exist yet (it publishes within a second of coming online). */
    static final int FOLLOW_ATTEMPTS = 10;

    /**
     * Connection thread: subscribes explicitly to the robot's telemetry nodes (XEP-0060; {@code +notify} alone is not
     * dependable on ejabberd). A node that does not exist yet is asked for again a second later.
     */
    private void follow(Session s, String jid, int attempt) {
        if (session != s) {
            return;
        }
        EntityBareJid robot;
        try {
            robot = JidCreate.entityBareFrom(jid);
        } catch (XmppStringprepException e) {
            return;
        }
        List<String> missing = new ArrayList<>();
        for (Resource<?, ?> r : TELEMETRY) {
            Outcome<Void> o = s.manager().telemetry().follow(robot, r);
            if (!o.isSuccess()) {
                missing.add(r.name() + " (" + o.errorOrNull() + ")");
            }
        }
        if (missing.isEmpty()) {
            LOG.info("following the telemetry of {}", jid);
        } else if (attempt + 1 < FOLLOW_ATTEMPTS) {
            connector.schedule(() -> follow(s, jid, attempt + 1), 1, TimeUnit.SECONDS);
        } else {
            LOG.warn("cannot subscribe to the telemetry of {}: {}", jid, missing);
        }
        fetchPlan(jid);
    }

    private void listenTelemetry(Session s) {
        ControlMlManager m = s.manager();
        m.telemetry().addListener(Resources.POSITION, (device, pose) -> {
            long receivedNanos = System.nanoTime(); // the lag's receipt: monotonic (RobotState.poseLag)
            update(device.toString(), r -> r.withPose(pose, clock.instant(), receivedNanos));
        });
        m.telemetry().addListener(Resources.VELOCITY, (device, v) -> update(device.toString(), r -> r.withVelocity(v
                .twist(), clock.instant())));
        m.telemetry().addListener(Resources.OBSTACLES, (device, o) -> update(device.toString(), r -> r.withObstacles(o,
                clock.instant())));
        m.telemetry().addListener(Resources.MISSION, (device, mission) -> {
            String jid = device.toString();
            RobotState before = robots.get(jid);
            update(jid, r -> r.withMission(mission, clock.instant()));
            // a new mission (or one seen for the first time) has a new plan
            boolean fresh = before != null && (before.mission() == null || before.mission().state() != mission
                    .state()) && mission.state().isActive();
            if (fresh) {
                fetchPlan(jid);
            }
        });
    }

    /** Asks the robot for its planned trajectory and goal (a goal of none is not an error: no plan to show). */
    private void fetchPlan(String jid) {
        CompletableFuture<TrajectoryPayload> path = get(jid, Resources.TRAJECTORY);
        CompletableFuture<Goal> goal = get(jid, Resources.GOAL);
        path.handle((t, e) -> t).thenCombine(goal.handle((g, e) -> g), (t, g) -> {
            update(jid, r -> r.withPlan(t != null && !t.points().isEmpty() ? t : null, g));
            return null;
        });
    }

    // ------------------------------------------------------------------------------------------------ state

    private void update(String jid, UnaryOperator<RobotState> change) {
        synchronized (stateLock) {
            RobotState before = robots.get(jid);
            if (before == null) {
                return; // telemetry or presence of someone not followed
            }
            RobotState after = change.apply(before);
            robots.put(jid, after);
            notifier.execute(() -> listeners.forEach(l -> l.robotChanged(after)));
        }
    }

    /** Only the roster adds robots. */
    private void add(String jid, String name) {
        synchronized (stateLock) {
            if (!robots.containsKey(jid)) {
                RobotState r = RobotState.unknown(jid, name);
                robots.put(jid, r);
                notifier.execute(() -> listeners.forEach(l -> l.robotChanged(r)));
            }
        }
    }

    private void remove(String jid) {
        synchronized (stateLock) {
            if (robots.remove(jid) != null) {
                notifier.execute(() -> listeners.forEach(l -> l.robotRemoved(jid)));
            }
        }
    }

    private void setStatus(State state, String account, String detail) {
        synchronized (stateLock) {
            ConnectionStatus s = new ConnectionStatus(state, account, detail, clock.instant());
            status = s;
            notifier.execute(() -> listeners.forEach(l -> l.connectionChanged(s)));
        }
    }

    /**
     * The fleet's threads, at {@link #BACKGROUND_PRIORITY}. Smack's reader, writer and executor threads are started
     * from them and inherit it.
     */
    private static ThreadFactory named(String name) {
        AtomicInteger n = new AtomicInteger();
        return r -> {
            Thread t = new Thread(r, name + "-" + n.incrementAndGet());
            t.setDaemon(true);
            t.setPriority(BACKGROUND_PRIORITY);
            return t;
        };
    }
}
