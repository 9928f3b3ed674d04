package sabot.onboard.controlml.internal.peers;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.time.Instant;
import java.time.LocalDate;
import java.util.ArrayDeque;
import java.util.Deque;
import java.util.Hashtable;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Optional;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.locks.LockSupport;
import java.util.function.BooleanSupplier;
import java.util.function.Predicate;
import java.util.function.Supplier;

import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.impl.JidCreate;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;
import org.osgi.service.cm.Configuration;
import org.osgi.service.cm.ConfigurationAdmin;
import org.osgi.util.tracker.ServiceTracker;

import sabot.controlml.AccessPolicy;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Resource;
import sabot.controlml.Resources;
import sabot.controlml.TelemetryLeases;
import sabot.controlml.TelemetryManager;
import sabot.controlml.TelemetryPublication;
import sabot.controlml.payload.PassageStatus;
import sabot.controlml.payload.PoseCovariance;
import sabot.controlml.payload.PoseEstimate;
import sabot.controlml.payload.VelocityCommand;
import sabot.fleet.AccessRules;
import sabot.fleet.FleetException;
import sabot.fleet.FleetLobby;
import sabot.fleet.SubscriptionGate;
import sabot.identity.DeviceIdentityManager;
import sabot.identity.DeviceProfile;
import sabot.identity.DeviceUrn;
import sabot.identity.Inventory;
import sabot.model.geometry.Pose2D;
import sabot.model.geometry.Twist2D;
import sabot.model.robot.PassageClaim;
import sabot.model.robot.PeerRobot;
import sabot.onboard.controlml.internal.session.ControlMlSettings;
import sabot.onboard.session.FleetPeers;
import sabot.onboard.session.RobotSession;
import sabot.onboard.task.OnboardTask;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * Robots that see each other, on a real server: robot A is the product's {@code controlml} and {@code peers} tasks,
 * configured through Config Admin as the onboard application does, with a fleet lobby; robot B is another robot as A
 * meets it on the wire ({@link WireRobot}: its own account, the roles a robot's default settings give, its telemetry
 * served with leases, in the lobby); the impostor is an account whose own vCard says "robot", in the lobby,
 * publishing a pose, that the server does not put in its robots' group. Run on Prosody and ejabberd.
 */
abstract class PeersOnServerTest {

    static final long WAIT_S = 20;
    static final String DOMAIN = PrivateXmppServer.DOMAIN;
    /** Robot B's pose and velocity as it publishes them, then after it moved. */
    static final Pose2D B_POSE = new Pose2D(3.25, 1.5, -0.5), B_MOVED = new Pose2D(4.75, 1.5, 0.25);
    static final Twist2D B_TWIST = new Twist2D(0.25, 0.1);
    /** Robot B's claim on a narrow passage (cm.passage), as it publishes it. */
    static final PassageClaim B_CLAIM = new PassageClaim(1, PassageClaim.State.WAITING, Instant.parse(
            "2026-11-30T10:15:30Z"));
    static final Pose2D IMPOSTOR_POSE = new Pose2D(1.0, 1.0, 0);
    /**
     * A robot's default telemetry rates, Hz: controlml.baseRate; positionRate and velocityRate; passageRate (the
     * tests of the controlml settings check those defaults).
     */
    static final double BASE_HZ = 0.2, FULL_HZ = 10, PASSAGE_HZ = 5;
    private static final AtomicInteger RUNS = new AtomicInteger();

    protected abstract PrivateXmppServer server();

    @TempDir
    Path dir;

    private final BundleContext context = FrameworkUtil.getBundle(PeersTask.class).getBundleContext();
    /** Every robot robot A's FleetPeers ever listed during the test. */
    private final Set<String> everListed = ConcurrentHashMap.newKeySet();
    /** What the test started, closed in the reverse order. */
    private final Deque<AutoCloseable> toClose = new ArrayDeque<>();
    private int run;
    private EntityBareJid robotA, robotB, lobby;
    private Configuration controlml, peersConfiguration;
    private RobotSession session;
    private FleetPeers peers;

    @BeforeEach
    void robotAFollowsItsPeers() throws Exception {
        run = RUNS.incrementAndGet();
        robotA = server().register("peers-a-" + run, DOMAIN, "peers-a-pw-" + run);
        robotB = server().register("peers-b-" + run, DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD);
        lobby = JidCreate.entityBareFrom("fleet-peers-" + run + "@conference." + DOMAIN);
        server().enrolRobot(robotA); // as the lab enrols its robots: the server's group sabot-robots

        Hashtable<String, Object> session = new Hashtable<>();
        session.put("server", "127.0.0.1");
        session.put("port", server().port());
        session.put("caFile", server().caFile().toString());
        session.put("jid", robotA.toString());
        session.put("passwordFile", privateFile("robot-a.pw", "peers-a-pw-" + run).toString());
        session.put("reconnectMin", 0.05);
        session.put("reconnectMax", 0.4);
        session.put("lobby", lobby.toString());
        session.put(OnboardTask.ROBOT_NAME, "peers-a");
        controlml = configure("sabot.task.controlml", session);
        this.session = service(RobotSession.class);
        await(this.session::isOnline, "robot A online");
        Hashtable<String, Object> settings = new Hashtable<>();
        settings.put(OnboardTask.ROBOT_NAME, "peers-a"); // the peers task's own settings at their defaults
        peersConfiguration = configure("sabot.task.peers", settings);
        peers = service(FleetPeers.class);
    }

    @AfterEach
    void stop() throws Exception {
        for (AutoCloseable c : toClose) {
            c.close();
        }
        for (Configuration c : new Configuration[] { peersConfiguration, controlml }) {
            if (c != null) {
                c.delete();
            }
        }
        await(() -> context.getServiceReference(FleetPeers.class) == null, "FleetPeers unregistered");
        await(() -> context.getServiceReference(RobotSession.class) == null, "RobotSession unregistered");
    }

    /**
     * Robot A follows robot B once the server puts B in its robots' group, with the pose and velocity B publishes,
     * leased at the peers task's rate (B grants it: a robot observes the others by default); never the impostor, whose
     * own vCard and telemetry say "robot" from the lobby, nor itself.
     */
    @Test
    void aRobotFollowsTheRobotsTheServerVouchesForAndNeverAnImpostorNorItself() throws Exception {
        XMPPTCPConnection impostor = impostorInTheLobby();
        awaitLobbyMember(impostor.getUser().toString(), "the impostor");
        WireRobot b = robot(B_POSE);
        awaitLobbyMember(b.connection.getUser().toString(), "robot B, not yet one of the lab's robots");

        Instant enrolled = Instant.now();
        server().enrolRobot(robotB); // the server's word
        PeerRobot heard = awaitPeer(p -> p.pose().equals(B_POSE) && p.velocity().equals(B_TWIST) && B_CLAIM.equals(
                p.passage()), "robot B with the pose, velocity and passage claim it publishes");
        assertTrue(heard.online());
        assertFalse(heard.heard().isBefore(enrolled), heard + " stamped before it was followed");
        assertFalse(heard.heard().isAfter(Instant.now()), heard + " stamped in the future");
        await(() -> b.rate(Resources.POSITION) == PeersSettings.DEFAULT_RATE_HZ && b.rate(Resources.VELOCITY)
                == PeersSettings.DEFAULT_RATE_HZ && b.rate(Resources.PASSAGE) == PeersSettings.DEFAULT_RATE_HZ,
                () -> "robot B publishing at the leased "
                        + PeersSettings.DEFAULT_RATE_HZ + " Hz, not at its base rate (its rates: " + b.leases.rates()
                        + ")");
        // poses keep coming at that rate: a later one is heard within a few periods, not after the base rate's 5 s
        await(() -> peer(robotB).map(p -> p.heard().isAfter(heard.heard())).orElse(false), "a later pose of B");

        assertEquals(List.of(robotB.toString()), listedNow().stream().map(PeerRobot::jid).toList());
        assertFalse(everListed.contains(impostor.getUser().asBareJid().toString()), "the impostor was followed");
        assertFalse(everListed.contains(robotA.toString()), "robot A followed itself");
        assertTrue(((OnboardTask) peers).status().startsWith("following 1 robot(s) of group "
                + AccessRules.ROBOTS_GROUP + " (1 online)"), ((OnboardTask) peers)::status);
    }

    /** A robot the server takes out of its robots' group is let go within seconds, though it is still online. */
    @Test
    void aRobotRemovedFromTheServersGroupIsLetGo() throws Exception {
        WireRobot b = robot(B_POSE);
        server().enrolRobot(robotB);
        awaitPeer(p -> p.pose().equals(B_POSE), "robot B followed");

        long removed = System.nanoTime();
        server().group("remove", AccessRules.ROBOTS_GROUP, robotB);
        await(() -> peer(robotB).isEmpty(), "robot B let go");
        System.out.printf(Locale.ROOT, "[figure] %s: a robot removed from the group let go after %.2f s%n", server()
                .kind(), (System.nanoTime() - removed) / 1e9);
        assertTrue(b.connection.isAuthenticated(), "it went offline: not what this test shows");
    }

    /**
     * A robot that goes offline stays with its last pose, marked offline (its body is still there); when it comes
     * back, it is followed again with its new pose and leased again.
     */
    @Test
    void aRobotThatGoesOfflineKeepsItsLastPoseMarkedOfflineAndIsFollowedAgainWhenBack() throws Exception {
        WireRobot b = robot(B_POSE);
        server().enrolRobot(robotB);
        awaitPeer(p -> p.pose().equals(B_POSE) && p.online(), "robot B followed");

        b.close();
        PeerRobot gone = awaitPeer(p -> !p.online(), "robot B marked offline");
        assertEquals(B_POSE, gone.pose(), "its last pose");
        assertEquals(B_TWIST, gone.velocity());

        WireRobot back = robot(B_MOVED);
        awaitPeer(p -> p.online() && p.pose().equals(B_MOVED), "robot B online again with its new pose");
        await(() -> back.rate(Resources.POSITION) == PeersSettings.DEFAULT_RATE_HZ, () -> "robot B leased again "
                + "(its new session had no lease; its rates: " + back.leases.rates() + ")");
    }

    /**
     * After robot A's session is lost and logs in again (the server restarted: nothing resumed, the lobby gone), it
     * joins the lobby again, and its subscriptions and leases are made again by themselves.
     */
    @Test
    void afterItsSessionReconnectsARobotFollowsItsPeersAgain() throws Exception {
        WireRobot b = robot(B_POSE);
        server().enrolRobot(robotB);
        awaitPeer(p -> p.pose().equals(B_POSE), "robot B followed");

        server().stopServer();
        await(() -> !session.isOnline(), "robot A offline");
        b.close();
        server().restart();
        await(session::isOnline, "robot A online again (by itself)");
        WireRobot back = robot(B_MOVED);
        awaitLobbyMember(back.connection.getUser().toString(), "robot B in the lobby that robot A joined again");
        awaitPeer(p -> p.online() && p.pose().equals(B_MOVED), "robot B's pose after the restart");
        await(() -> back.rate(Resources.POSITION) == PeersSettings.DEFAULT_RATE_HZ, () -> "robot B leased again "
                + "(its rates: " + back.leases.rates() + ")");
    }

    // ------------------------------------------------------------------------------------------ the other robots

    /**
     * Another robot of the lab as robot A meets it on the wire: its account's session with the roles a robot's
     * default settings give ({@link ControlMlSettings}: the lab's robots observe it), its position, velocity and
     * passage claim served with leases at a robot's default rates, in the fleet lobby.
     */
    final class WireRobot implements AutoCloseable {
        final XMPPTCPConnection connection;
        final TelemetryLeases leases;

        WireRobot(Pose2D pose) throws Exception {
            connection = new XMPPTCPConnection(server().configuration(robotB.getLocalpart().toString(), DOMAIN,
                    PrivateXmppServer.DEFAULT_PASSWORD).build());
            ControlMlSettings defaults = ControlMlSettings.of(Map.of("jid", robotB.toString(), "passwordFile",
                    privateFile("robot-b.pw", PrivateXmppServer.DEFAULT_PASSWORD).toString()));
            AccessPolicy policy = defaults.access().on(connection);
            SubscriptionGate.onDevice(connection, policy);
            ControlMlManager manager = ControlMlManager.getInstanceFor(connection);
            manager.setAccessPolicy(policy);
            server().connect(connection);
            leases = manager.telemetry().serveLeases(60);
            leases.offer(Resources.POSITION, () -> new PoseEstimate(Instant.now(), pose, PoseCovariance.diagonal(
                    0.01, 0.01, 0.001)), BASE_HZ, FULL_HZ);
            leases.offer(Resources.VELOCITY, () -> new VelocityCommand(Instant.now(), B_TWIST), BASE_HZ, FULL_HZ);
            leases.offer(Resources.PASSAGE, () -> new PassageStatus(Instant.now(), Optional.of(B_CLAIM)), BASE_HZ,
                    PASSAGE_HZ);
            joinTheLobby(connection);
        }

        /** @return the rate it publishes a resource at now, Hz */
        double rate(Resource<?, ?> resource) {
            return leases.rates().stream(resource.name()).rate();
        }

        @Override
        public void close() {
            leases.close();
            connection.disconnect();
        }
    }

    private WireRobot robot(Pose2D pose) throws Exception {
        WireRobot r = new WireRobot(pose);
        toClose.push(r);
        return r;
    }

    /**
     * @return an account that claims to be one of the lab's robots: its vCard says so, it joins the fleet lobby,
     *         publishes a pose and asks robot A for its presence; the server's robots' group does not hold it
     */
    private XMPPTCPConnection impostorInTheLobby() throws Exception {
        String name = "peers-imp-" + run;
        XMPPTCPConnection c = server().login(name);
        toClose.push(c::disconnect);
        DeviceProfile profile = new DeviceProfile("mobile robot (differential drive)", "Sabot", "R2", name, null,
                null, null, DeviceUrn.urnOf("SN-" + name), c.getUser().asBareJid().toString(), "robot", LocalDate.of(
                        2026, 11, 21), null, null);
        Inventory inventory = new Inventory(1, profile.uid(), new Inventory.Mechanic("chassis", List.of()), List.of(
                new Inventory.Board("pc", "x86_64", null, List.of(), List.of(new Inventory.Item("sabot.onboard",
                        "0.1.0")), List.of())), List.of());
        DeviceIdentityManager.getInstanceFor(c).publish(profile, inventory).orElseThrow();
        TelemetryPublication claimed = TelemetryManager.getInstanceFor(c).publish(Resources.POSITION,
                () -> new PoseEstimate(Instant.now(), IMPOSTOR_POSE, PoseCovariance.ZERO), FULL_HZ);
        toClose.push(claimed::stop);
        Roster.getInstanceFor(c).sendSubscriptionRequest(robotA);
        joinTheLobby(c);
        return c;
    }

    /**
     * Joins the fleet lobby as a device does: again while it is refused, as it is while another device that made it
     * has not configured it yet (robot A's session joins it at the same time).
     */
    private void joinTheLobby(XMPPTCPConnection c) throws FleetException {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(WAIT_S);
        FleetLobby room = new FleetLobby(c, lobby);
        while (true) {
            try {
                room.join();
                return;
            } catch (FleetException e) {
                if (System.nanoTime() - deadline > 0) {
                    throw e;
                }
                LockSupport.parkNanos(TimeUnit.MILLISECONDS.toNanos(50));
            }
        }
    }

    // ------------------------------------------------------------------------------------------ helpers

    /** @return robot A's FleetPeers now (every robot listed is remembered for the test's end) */
    private List<PeerRobot> listedNow() {
        List<PeerRobot> now = peers.peers();
        now.forEach(p -> everListed.add(p.jid()));
        return now;
    }

    private Optional<PeerRobot> peer(EntityBareJid jid) {
        return listedNow().stream().filter(p -> p.jid().equals(jid.toString())).findFirst();
    }

    /** @return robot B's entry in robot A's FleetPeers once it matches, waited for up to {@link #WAIT_S} */
    private PeerRobot awaitPeer(Predicate<PeerRobot> condition, String what) {
        PeerRobot[] found = new PeerRobot[1];
        await(() -> {
            found[0] = peer(robotB).filter(condition).orElse(null);
            return found[0] != null;
        }, () -> what + " in robot A's FleetPeers (listed: " + peers.peers() + ")");
        return found[0];
    }

    private void awaitLobbyMember(String fullJid, String what) {
        await(() -> session.lobbyMembers().contains(fullJid), what + " among robot A's lobby members");
    }

    private Configuration configure(String pid, Hashtable<String, Object> properties) throws Exception {
        Configuration c = service(ConfigurationAdmin.class).getConfiguration(pid, "?");
        c.update(properties);
        return c;
    }

    private Path privateFile(String name, String content) throws Exception {
        Path f = dir.resolve(name);
        Files.writeString(f, content + "\n");
        Files.setPosixFilePermissions(f, PosixFilePermissions.fromString("rw-------"));
        return f;
    }

    private <S> S service(Class<S> type) throws InterruptedException {
        ServiceTracker<S, S> t = new ServiceTracker<>(context, type, null);
        t.open();
        S s = t.waitForService(TimeUnit.SECONDS.toMillis(WAIT_S));
        assertNotNull(s, type.getSimpleName() + " not available within " + WAIT_S + " s");
        return s;
    }

    private static void await(BooleanSupplier condition, String what) {
        await(condition, () -> what);
    }

    /**
     * Polls a condition (services, snapshots and rates have no event of their own for a test) until a deadline.
     *
     * @param what what is waited for, told as the deadline passes
     */
    private static void await(BooleanSupplier condition, Supplier<String> what) {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(WAIT_S);
        while (!condition.getAsBoolean()) {
            if (System.nanoTime() - deadline > 0) {
                throw new AssertionError(what.get() + " within " + WAIT_S + " s");
            }
            LockSupport.parkNanos(TimeUnit.MILLISECONDS.toNanos(10));
        }
    }
}
