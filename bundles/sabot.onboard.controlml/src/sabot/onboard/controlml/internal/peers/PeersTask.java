package sabot.onboard.controlml.internal.peers;

import java.time.Clock;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Collections;
import java.util.HashMap;
import java.util.HashSet;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.Executors;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;

import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.RosterEntry;
import org.jivesoftware.smack.roster.RosterGroup;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.Jid;
import org.jxmpp.jid.impl.JidCreate;
import org.jxmpp.stringprep.XmppStringprepException;
import org.osgi.service.component.annotations.Activate;
import org.osgi.service.component.annotations.Component;
import org.osgi.service.component.annotations.ConfigurationPolicy;
import org.osgi.service.component.annotations.Deactivate;
import org.osgi.service.component.annotations.Reference;
import org.osgi.service.metatype.annotations.Designate;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.ControlMl;
import sabot.controlml.Outcome;
import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.TelemetryManager;
import sabot.controlml.TelemetryWatcher;
import sabot.fleet.RosterEntriesListener;
import sabot.model.robot.PeerRobot;
import sabot.onboard.session.FleetPeers;
import sabot.onboard.session.RobotSession;
import sabot.onboard.session.SessionListener;
import sabot.onboard.task.NamedThreads;
import sabot.onboard.task.OnboardTask;

/**
 * The {@code peers} task: this robot follows the other robots of the lab over its session (roster rules 11 and 12,
 * docs/CONTROLML.md) and offers what it hears as {@link FleetPeers}, for the motion task's costmap and collision guard.
 * <p>
 * <b>Who.</b> A robot is one the server vouches for: its roster entry in the server's shared group of robots
 * ({@link PeersSettings#group}, written by the server, never by the account), not an account whose own vCard says
 * "robot". The candidates are the fleet lobby's occupants ({@link RobotSession#lobbyMembers}) and the roster's
 * contacts with an available presence; never this robot itself. A robot is followed from the moment it is both; it
 * stays followed, marked offline with its last pose (its body is still there), while it is offline, and is let go when
 * it leaves the group.
 * <p>
 * <b>How.</b> For each followed robot: explicit XEP-0060 subscriptions to its {@code cm.position},
 * {@code cm.velocity} and {@code cm.passage} nodes (its claim on a narrow passage, docs/PASSAGES.md;
 * {@link TelemetryManager#follow}; a node not published yet is asked for again, 1 s after, doubling to 30 s), and a
 * lease of the three at {@link PeersSettings#rateHz} at its full JID ({@link TelemetryWatcher},
 * renewed at half of what the robot grants; sent again when the robot comes back online). A robot lets this one lease
 * its telemetry because the lab's robots observe one another by default ({@code controlml.observerGroups}); an
 * observer cannot command. Each pose is stamped with this robot's clock when it arrives ({@link PeerBook}). After this
 * robot's session reconnects, every subscription and lease is made again.
 * <p>
 * <b>Threads.</b> The roster's and the session's events only ask for a reconciliation; it runs on the thread
 * {@code sabot-peers} (where subscriptions wait for their answers), then and every {@link #RECONCILE}, which also
 * notices the lobby's comings and goings. Telemetry arrives on Smack's listener thread straight into the book. The
 * telemetry listeners stay on the session's manager after a deactivation (a manager's listeners are registered once,
 * for the session's life): they then find no robot followed and drop every item.
 * <p>
 * Settings: {@link PeersSettings.Config}, checked by {@link PeersSettingsCheck}.
 */
@Designate(ocd = PeersSettings.Config.class, factory = false)
@Component(name = "sabot.task.peers", configurationPolicy = ConfigurationPolicy.REQUIRE, immediate = true,
        service = { OnboardTask.class, FleetPeers.class })
public final class PeersTask implements OnboardTask, FleetPeers {

    private static final Logger LOG = LoggerFactory.getLogger(PeersTask.class);

    /** The telemetry followed of each robot. */
    static final List<Resource<?, ?>> FOLLOWED = List.of(Resources.POSITION, Resources.VELOCITY, Resources.PASSAGE);
    /** The lease asked of each robot, s; the watcher renews it at half of what the robot grants. */
    static final double LEASE_S = 30;
    /** How often who is followed is checked without an event: the lobby's comings and goings, subscriptions retried. */
    static final Duration RECONCILE = Duration.ofSeconds(1);
    /** First and longest delay before a robot's telemetry nodes that do not exist yet are asked for again. */
    static final Duration SUBSCRIBE_RETRY_MIN = Duration.ofSeconds(1), SUBSCRIBE_RETRY_MAX = Duration.ofSeconds(30);
    /** Failed subscriptions in a row to a robot after which they are logged as a warning (once). */
    static final int SUBSCRIBE_WARN_AFTER = 10;
    /**
     * After this robot's login, how long a followed robot without a presence yet is not taken as offline: the
     * contacts' presences arrive after the login, a lost session's roster took them all as offline.
     */
    static final Duration PRESENCES_SETTLE = Duration.ofSeconds(3);

    /** One followed robot, as the worker thread knows it. */
    private static final class Followed {
        final EntityBareJid jid;
        /** The full JID its lease was sent to; null before the first. */
        Jid leasedAt;
        boolean online;
        /** The telemetry nodes subscribed to (each asked for until it is). */
        final Set<Resource<?, ?>> subscribed = new HashSet<>();
        /** The lease is to be sent again (the robot, or this session, came back online: it has none). */
        boolean renewLease;
        int failures;
        /** System.nanoTime() from which a failed subscription is asked for again; meaningful once failures > 0. */
        long retryAtNanos;

        Followed(EntityBareJid jid) {
            this.jid = jid;
        }
    }

    private final RobotSession session;
    private final PeersSettings settings;
    private final PeerBook book;
    private final Roster roster;
    private final TelemetryManager telemetry;
    private final TelemetryWatcher watcher;
    /** The lease asked of every robot, in a fixed order (a watcher sends again only what differs). */
    private final Map<Resource<?, ?>, Double> rates;
    private final ScheduledExecutorService worker = Executors.newSingleThreadScheduledExecutor(NamedThreads.daemon(
            "sabot-peers"));
    private final AtomicBoolean reconcilePending = new AtomicBoolean();
    private final RosterEvents rosterEvents = new RosterEvents();
    private final SessionListener sessionEvents = new SessionListener() {
        @Override
        public void online() {
            run(PeersTask.this::sessionOnline);
        }

        @Override
        public void offline(String reason) {
            // nothing to do until it is back: the robots' entries keep their last poses and their age shows
        }
    };
    /** Worker thread only: the followed robots by bare JID. */
    private final Map<String, Followed> followed = new HashMap<>();
    /** Worker thread only (set before it starts): System.nanoTime() of this session's last login. */
    private long loginNanos;
    private volatile boolean stopped;
    private volatile int followedCount;
    private volatile int onlineCount;

    /**
     * @param session    the robot's XMPP session
     * @param properties the task's configuration ({@link PeersSettings.Config})
     */
    @Activate
    public PeersTask(@Reference(name = "session") RobotSession session, Map<String, Object> properties) {
        this.settings = PeersSettings.of(properties);
        this.session = session;
        this.book = new PeerBook(Clock.systemUTC());
        Map<Resource<?, ?>, Double> asked = new LinkedHashMap<>();
        FOLLOWED.forEach(r -> asked.put(r, settings.rateHz()));
        this.rates = Collections.unmodifiableMap(asked);
        this.telemetry = session.controlMl().telemetry();
        this.roster = Roster.getInstanceFor(session.connection());
        telemetry.addListener(Resources.POSITION, (device, estimate) -> book.pose(device.toString(), estimate.pose()));
        telemetry.addListener(Resources.VELOCITY, (device, command) -> book.velocity(device.toString(), command
                .twist()));
        telemetry.addListener(Resources.PASSAGE, (device, status) -> book.passage(device.toString(), status.claim()
                .orElse(null)));
        this.watcher = telemetry.watcher(LEASE_S);
        loginNanos = System.nanoTime();
        roster.addRosterListener(rosterEvents);
        session.addListener(sessionEvents); // told online() at once when the session is online already
        worker.scheduleWithFixedDelay(this::reconcile, RECONCILE.toNanos(), RECONCILE.toNanos(),
                TimeUnit.NANOSECONDS);
        LOG.info("peers task started: following the robots of the server's group {} (online in the roster or the "
                + "fleet lobby), their position, velocity and passage claim at {} Hz", settings.group(), settings
                        .rateHz());
    }

    @Deactivate
    void deactivate() {
        stopped = true;
        session.removeListener(sessionEvents);
        roster.removeRosterListener(rosterEvents);
        worker.shutdownNow();
        try {
            // a subscription in progress ends within the request timeout
            worker.awaitTermination(ControlMl.DEFAULT_REQUEST_TIMEOUT_S + 1, TimeUnit.SECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        book.clear();
        watcher.close(); // every lease ended, each robot told
        if (session.isOnline()) {
            for (Followed f : followed.values()) {
                unsubscribe(f);
            }
        }
        LOG.info("peers task stopped: {} robot(s) let go", followed.size());
        followed.clear();
    }

    // ------------------------------------------------------------------------------------------ FleetPeers

    @Override
    public List<PeerRobot> peers() {
        return book.peers();
    }

    // ------------------------------------------------------------------------------------------ OnboardTask

    @Override
    public String name() {
        return PeersSettings.TASK;
    }

    @Override
    public String status() {
        return "following " + followedCount + " robot(s) of group " + settings.group() + " (" + onlineCount
                + " online), position, velocity and passage claim at " + settings.rateHz() + " Hz";
    }

    // ------------------------------------------------------------------------------------------ worker thread

    /** This robot's session logged in (again): every subscription and lease is made again. */
    private void sessionOnline() {
        loginNanos = System.nanoTime();
        for (Followed f : followed.values()) {
            f.subscribed.clear();
            f.failures = 0;
            f.renewLease = true;
        }
        reconcile();
    }

    /** Who is followed, brought to what the roster and the lobby say now. */
    private void reconcile() {
        reconcilePending.set(false);
        if (stopped || !session.isOnline() || !session.connection().isAuthenticated()) {
            return; // a lost session's roster has every presence offline: it would undo what is known
        }
        try {
            Set<String> robots = robotsOfTheGroup();
            Map<String, Jid> online = onlineCandidates();
            for (Followed f : new ArrayList<>(followed.values())) {
                if (!robots.contains(f.jid.toString())) {
                    stopFollowing(f, "it is no longer in the server's group " + settings.group());
                }
            }
            for (String jid : online.keySet()) {
                if (robots.contains(jid) && !followed.containsKey(jid)) {
                    startFollowing(jid);
                }
            }
            boolean settling = System.nanoTime() - loginNanos < PRESENCES_SETTLE.toNanos();
            int up = 0;
            for (Followed f : followed.values()) {
                Jid at = online.get(f.jid.toString());
                if (at == null && settling && f.online) {
                    up++;
                    continue; // its presence may not have arrived yet
                }
                if (at != null && !f.online) {
                    // (back) online: a new session of the robot, which has no lease, and nodes perhaps new
                    f.subscribed.clear();
                    f.failures = 0;
                    f.renewLease = true;
                }
                f.online = at != null;
                book.online(f.jid.toString(), f.online);
                if (f.online) {
                    up++;
                    subscribe(f);
                    lease(f, at);
                }
            }
            followedCount = followed.size();
            onlineCount = up;
        } catch (RuntimeException e) {
            LOG.warn("peers: the followed robots could not be brought up to date (tried again in {} s)", RECONCILE
                    .toMillis() / 1000.0, e);
        }
    }

    /** @return the bare JIDs that this robot's roster puts in the robots' group (the server's word), but its own */
    private Set<String> robotsOfTheGroup() {
        Set<String> robots = new HashSet<>();
        RosterGroup group = roster.getGroup(settings.group());
        if (group != null) {
            for (RosterEntry e : group.getEntries()) {
                robots.add(e.getJid().asBareJid().toString());
            }
        }
        robots.remove(session.jid());
        return robots;
    }

    /**
     * @return the candidates online, by bare JID: the lobby's occupants and the roster's contacts with an available
     *         presence (whose full JID, the robot's session, is preferred), but this robot
     */
    private Map<String, Jid> onlineCandidates() {
        Map<String, Jid> online = new HashMap<>();
        for (String member : session.lobbyMembers()) {
            try {
                Jid jid = JidCreate.from(member);
                if (jid.hasResource()) {
                    online.put(jid.asBareJid().toString(), jid);
                }
            } catch (XmppStringprepException e) {
                LOG.debug("fleet lobby occupant '{}' is no JID: {}", member, e.getMessage());
            }
        }
        for (RosterEntry e : roster.getEntries()) {
            Presence p = roster.getPresence(e.getJid());
            if (p.isAvailable() && p.getFrom() != null && p.getFrom().hasResource()) {
                online.put(e.getJid().asBareJid().toString(), p.getFrom());
            }
        }
        online.remove(session.jid());
        return online;
    }

    private void startFollowing(String bare) {
        EntityBareJid jid;
        try {
            jid = JidCreate.entityBareFrom(bare);
        } catch (XmppStringprepException e) {
            return; // a roster's entry is a JID
        }
        followed.put(bare, new Followed(jid));
        book.follow(bare);
        LOG.info("following {} (in the server's group {}): position, velocity and passage claim at {} Hz", bare,
                settings.group(), settings.rateHz());
    }

    private void stopFollowing(Followed f, String why) {
        String bare = f.jid.toString();
        followed.remove(bare);
        book.unfollow(bare); // first: the motion task forgets it at once
        if (f.leasedAt != null) {
            watcher.watch(f.leasedAt, Map.of()); // lease 0: it falls back to its base rate
        }
        unsubscribe(f);
        LOG.info("no longer following {}: {}", bare, why);
    }

    /** Subscribes to the robot's telemetry nodes not subscribed to yet, unless waiting to ask again. */
    private void subscribe(Followed f) {
        if (f.subscribed.size() == FOLLOWED.size() || (f.failures > 0 && System.nanoTime() - f.retryAtNanos < 0)) {
            return;
        }
        List<String> missing = new ArrayList<>();
        for (Resource<?, ?> r : FOLLOWED) {
            if (f.subscribed.contains(r)) {
                continue;
            }
            Outcome<Void> o = telemetry.follow(f.jid, r);
            if (o.isSuccess()) {
                f.subscribed.add(r);
            } else {
                missing.add(r.name() + " (" + o.errorOrNull() + ")");
            }
        }
        if (missing.isEmpty()) {
            f.failures = 0;
            LOG.debug("subscribed to the telemetry of {}", f.jid);
            return;
        }
        f.failures++;
        Duration delay = retryDelay(f.failures);
        f.retryAtNanos = System.nanoTime() + delay.toNanos();
        if (f.failures == SUBSCRIBE_WARN_AFTER) {
            LOG.warn("cannot subscribe to the telemetry of {} after {} attempts: {}; asking again every {} s at most",
                    f.jid, f.failures, missing, SUBSCRIBE_RETRY_MAX.toMillis() / 1000.0);
        } else {
            LOG.debug("telemetry of {} not subscribed to (attempt {}): {}; again in {} s", f.jid, f.failures, missing,
                    delay.toMillis() / 1000.0);
        }
    }

    /** @return the delay after the n-th failed subscription in a row: the minimum, doubling, capped at the maximum */
    static Duration retryDelay(int failures) {
        Duration d = SUBSCRIBE_RETRY_MIN;
        for (int i = 1; i < failures && d.compareTo(SUBSCRIBE_RETRY_MAX) < 0; i++) {
            d = d.multipliedBy(2);
        }
        return d.compareTo(SUBSCRIBE_RETRY_MAX) > 0 ? SUBSCRIBE_RETRY_MAX : d;
    }

    /** Leases the robot's telemetry at its session's full JID {@code at}: sent when new, or again when asked to. */
    private void lease(Followed f, Jid at) {
        if (!at.equals(f.leasedAt)) {
            if (f.leasedAt != null) {
                watcher.watch(f.leasedAt, Map.of()); // a session of the robot that is gone
            }
            watcher.watch(at, rates);
            f.leasedAt = at;
        } else if (f.renewLease) {
            watcher.renew(at);
        }
        f.renewLease = false;
    }

    private void unsubscribe(Followed f) {
        for (Resource<?, ?> r : FOLLOWED) {
            // the server may have ended it already, with the presence subscription of the group
            Outcome<Void> o = telemetry.unfollow(f.jid, r);
            if (!o.isSuccess()) {
                LOG.debug("unsubscribing from {} of {}: {}", r.name(), f.jid, o.errorOrNull());
            }
        }
    }

    private void scheduleReconcile() {
        if (reconcilePending.compareAndSet(false, true)) {
            run(this::reconcile);
        }
    }

    private void run(Runnable action) {
        try {
            worker.execute(action);
        } catch (RejectedExecutionException stopped) {
            // deactivated meanwhile
        }
    }

    /** The roster's changes (the group's members) and presences: a reconciliation, on the worker thread. */
    private final class RosterEvents extends RosterEntriesListener {
        @Override
        protected void entriesChanged() {
            scheduleReconcile();
        }

        @Override
        public void presenceChanged(Presence presence) {
            scheduleReconcile();
        }
    }
}
