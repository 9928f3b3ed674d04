package sabot.onboard.controlml.internal.session;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.nio.file.Files;
import java.nio.file.Path;
import java.nio.file.attribute.PosixFilePermissions;
import java.util.Hashtable;
import java.util.List;
import java.util.Random;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;
import org.junit.jupiter.api.io.TempDir;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.EntityFullJid;
import org.jxmpp.jid.impl.JidCreate;
import org.osgi.framework.BundleContext;
import org.osgi.framework.FrameworkUtil;
import org.osgi.service.cm.Configuration;
import org.osgi.service.cm.ConfigurationAdmin;
import org.osgi.util.tracker.ServiceTracker;

import sabot.controlml.ControlMlManager;
import sabot.controlml.PresenceLevel;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.payload.FileChunk;
import sabot.controlml.payload.FileQuery;
import sabot.identity.DeviceCard;
import sabot.identity.DeviceIdentityManager;
import sabot.identity.DeviceUrn;
import sabot.identity.IdentityResult;
import sabot.onboard.session.RobotSession;
import sabot.onboard.session.SessionListener;
import sabot.onboard.task.OnboardTask;
import sabot.testsupport.net.SilentRelay;
import sabot.testsupport.xmpp.PrivateXmppServer;
import sabot.testsupport.xmpp.TestCertificates;

/**
 * The controlml and remotefs tasks configured through Config Admin, as the onboard application does, against a real
 * private Prosody; an operator's Smack client sees what the robot publishes.
 */
class ControlMlSessionOnProsodyTest {

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.prosody();

    static final long WAIT_S = 20;
    private static int accounts;

    private final BundleContext context = FrameworkUtil.getBundle(ControlMlSession.class).getBundleContext();
    private final BlockingQueue<String> events = new LinkedBlockingQueue<>();
    private final BlockingQueue<Presence> robotPresences = new LinkedBlockingQueue<>();
    private final BlockingQueue<String> offlineReasons = new LinkedBlockingQueue<>();

    @TempDir
    Path dir;

    EntityBareJid robot;
    EntityBareJid operator;
    /** The session's fleet lobby (controlml.lobby), or null for none. */
    EntityBareJid lobby;
    Configuration controlml;
    Configuration remotefs;
    XMPPTCPConnection operatorConnection;

    @BeforeEach
    void accounts() throws Exception {
        int n = ++accounts;
        String robotName = "robot-" + n;
        robot = XMPP.register(robotName, PrivateXmppServer.DOMAIN, "robot-pw-" + n);
        operator = JidCreate.entityBareFrom("op-" + n + "@" + PrivateXmppServer.DOMAIN);
        // as a lab's administrator: the robot in the robots' group, the operator's account a maintainer of them
        XMPP.enrolRobot(robot);
        XMPP.grant(operator, Role.MAINTAINER);
    }

    @AfterEach
    void stopTasks() throws Exception {
        if (operatorConnection != null) {
            operatorConnection.disconnect();
        }
        for (Configuration c : new Configuration[] { remotefs, controlml }) {
            if (c != null) {
                c.delete();
            }
        }
        awaitNoService(OnboardTask.class);
        awaitNoService(RobotSession.class);
    }

    Path passwordFile(String password, String mode) throws Exception {
        Path f = dir.resolve("robot.pw");
        Files.writeString(f, password + "\n");
        Files.setPosixFilePermissions(f, PosixFilePermissions.fromString(mode));
        return f;
    }

    RobotSession startControlMl() throws Exception {
        return startControlMl(XMPP.port(), ControlMlSettings.DEFAULT_LIVENESS_S);
    }

    RobotSession startControlMl(int port, double liveness) throws Exception {
        return startControlMl(port, liveness, XMPP.caFile());
    }

    RobotSession startControlMl(int port, double liveness, Path caFile) throws Exception {
        Hashtable<String, Object> props = new Hashtable<>();
        props.put("server", "127.0.0.1");
        props.put("port", port);
        props.put("caFile", caFile.toString());
        props.put("liveness", liveness);
        props.put("jid", robot.toString());
        props.put("passwordFile", passwordFile("robot-pw-" + accounts, "rw-------").toString());
        props.put("reconnectMin", 0.05);
        props.put("reconnectMax", 0.4);
        props.put(OnboardTask.ROBOT_NAME, "sabot-test");
        if (lobby != null) {
            props.put("lobby", lobby.toString());
        }
        controlml = service(ConfigurationAdmin.class).getConfiguration("sabot.task.controlml", "?");
        controlml.update(props);
        RobotSession session = service(RobotSession.class);
        session.addListener(new SessionListener() {
            @Override
            public void online() {
                events.add("online");
            }

            @Override
            public void offline(String reason) {
                offlineReasons.add(reason);
                events.add("offline");
            }
        });
        return session;
    }

    /** The operator logs in (again), following the robot's presence; its roster accepts the robot's request. */
    void operatorLogsIn() throws Exception {
        if (operatorConnection == null) {
            XMPP.register(operator.getLocalpart().toString(), PrivateXmppServer.DOMAIN,
                    PrivateXmppServer.DEFAULT_PASSWORD);
        }
        operatorConnection = new XMPPTCPConnection(XMPP.configuration(operator.getLocalpart().toString(),
                PrivateXmppServer.DOMAIN, PrivateXmppServer.DEFAULT_PASSWORD).build());
        Roster.getInstanceFor(operatorConnection).setSubscriptionMode(Roster.SubscriptionMode.accept_all);
        operatorConnection.addAsyncStanzaListener(s -> robotPresences.add((Presence) s), s -> s instanceof Presence
                && s.getFrom() != null && s.getFrom().asBareJid().equals(robot));
        operatorConnection.connect().login();
    }

    /** Waits for the robot's presence showing a mode and status (the server may repeat an earlier one first). */
    void awaitPresence(Presence.Mode mode, String status) throws InterruptedException {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(WAIT_S);
        List<String> seen = new java.util.ArrayList<>();
        while (System.nanoTime() < deadline) {
            Presence p = robotPresences.poll(deadline - System.nanoTime(), TimeUnit.NANOSECONDS);
            if (p == null) {
                break;
            }
            if (p.isAvailable() && p.getMode() == mode && status.equals(p.getStatus())) {
                return;
            }
            seen.add(p.getType() + "/" + p.getMode() + "/" + p.getStatus());
        }
        throw new AssertionError("no presence " + mode + " '" + status + "' from " + robot + " within " + WAIT_S
                + " s; seen " + seen);
    }

    void assertNextEvent(String expected) throws InterruptedException {
        assertEquals(expected, events.poll(WAIT_S, TimeUnit.SECONDS), "session event");
    }

    DeviceCard vCard() {
        IdentityResult<DeviceCard> card = DeviceIdentityManager.getInstanceFor(operatorConnection).fetch(robot);
        assertTrue(card instanceof IdentityResult.Ok, card::toString);
        return card.orElseThrow();
    }

    void assertIdentity(DeviceCard card) {
        assertEquals(robot.toString(), card.profile().jid());
        assertEquals("sabot-test", card.profile().nickname());
        assertEquals(DeviceUrn.urnOf(robot.toString()), card.profile().uid());
        assertEquals("robot", card.profile().role());
        assertNull(card.inventoryProblem(), "the QR inventory decodes");
        assertNotNull(card.inventory());
        assertTrue(card.inventory().boards().get(0).applications().stream().anyMatch(i -> i.name().equals(
                "sabot.onboard")), () -> card.inventory().boards().get(0).applications().toString());
    }

    /**
     * A link that goes silent — nothing passes, nothing is closed (a relay that stops forwarding) — is taken as a loss
     * within 2¼ liveness intervals, and the session is back online once traffic passes again.
     */
    /**
     * A server whose certificate is not signed by the configured CA: the session stays offline and says why in one
     * line (its status and its log), retrying; it never falls back to a plain or unchecked connection.
     */
    @Test
    void aServerCertificateFromAnotherCaIsRefusedWithOneLine() throws Exception {
        Path other = TestCertificates.anotherCa(dir, "another-ca");
        RobotSession session = startControlMl(XMPP.port(), ControlMlSettings.DEFAULT_LIVENESS_S, other);
        OnboardTask task = (OnboardTask) session;
        String expected = "the certificate for sabot.local is not signed by the CA of " + other + " (SHA-256 "
                + sabot.fleet.ServerTrust.labCa(other).fingerprints().get(0) + ")";
        // the status is updated after each attempt, with no event of its own: polled as the registry is
        awaitCondition(() -> task.status().contains(expected), "the refusal in the session's status");
        assertEquals("offline (" + expected + "), reconnecting", task.status());
        assertFalse(session.isOnline());
        assertTrue(events.isEmpty(), "no session event: " + events);
    }

    @Test
    void aSilentLinkIsTakenAsALossAndTheSessionComesBackWhenItPassesAgain() throws Exception {
        double liveness = 0.4;
        try (SilentRelay relay = new SilentRelay(XMPP.port())) {
            RobotSession session = startControlMl(relay.port(), liveness);
            assertNextEvent("online");
            // an idle link stays up: the pings answer for it
            TimeUnit.MILLISECONDS.sleep(Math.round(3 * liveness * 1000)); // the stimulus: idle time
            assertTrue(session.isOnline());
            assertTrue(events.isEmpty(), "an idle link was taken as lost: " + events);

            long silenced = System.nanoTime();
            relay.silence();
            assertNextEvent("offline");
            double noticed = (System.nanoTime() - silenced) / 1e9;
            String reason = offlineReasons.poll();
            assertTrue(reason != null && reason.startsWith("connection silent for"), reason);
            System.out.printf(java.util.Locale.ROOT, "[figure] silent link noticed after %.2f s (liveness %.1f s)%n",
                    noticed, liveness);
            // the silence counts from the last stanza received, up to one interval before the relay went quiet
            assertFalse(session.isOnline());

            relay.resume();
            assertNextEvent("online");
            assertTrue(session.isOnline());
        }
    }

    /**
     * The fleet lobby ({@code controlml.lobby}, roster rule 11): the session joins it after its login, where the robot
     * and an operator's client find each other; after a loss (a silent link) it is back there with the session, and
     * knows nobody there while offline.
     */
    @Test
    void theSessionJoinsTheFleetLobbyAndIsBackThereAfterALoss() throws Exception {
        lobby = JidCreate.entityBareFrom("fleet-session-" + accounts + "@conference." + PrivateXmppServer.DOMAIN);
        double liveness = 0.4;
        try (SilentRelay relay = new SilentRelay(XMPP.port())) {
            RobotSession session = startControlMl(relay.port(), liveness);
            assertNextEvent("online");
            operatorLogsIn();
            sabot.fleet.FleetLobby operatorInLobby = joinLobby(operatorConnection);
            String operatorJid = operatorConnection.getUser().toString();
            String robotJid = robot + "/" + ControlMlSettings.DEFAULT_RESOURCE;
            awaitCondition(() -> session.lobbyMembers().contains(operatorJid), "the operator among the robot's "
                    + "lobby members");
            awaitCondition(() -> operatorInLobby.members().stream().anyMatch(j -> j.toString().equals(robotJid)),
                    "the robot among the operator's lobby members");
            assertFalse(session.lobbyMembers().contains(robotJid), "the robot is no member of its own lobby");

            relay.silence();
            assertNextEvent("offline");
            assertEquals(List.of(), session.lobbyMembers(), "nobody known in the lobby while offline");
            relay.resume();
            assertNextEvent("online");
            awaitCondition(() -> session.lobbyMembers().contains(operatorJid), "the operator among the robot's "
                    + "lobby members again");
            awaitCondition(() -> operatorInLobby.members().stream().anyMatch(j -> j.toString().equals(robotJid)),
                    "the robot in the lobby again");
        }
    }

    /** The operator joins the lobby, again while it is refused (the robot may be making it at the same moment). */
    sabot.fleet.FleetLobby joinLobby(XMPPTCPConnection c) throws Exception {
        sabot.fleet.FleetLobby room = new sabot.fleet.FleetLobby(c, lobby);
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(WAIT_S);
        while (true) {
            try {
                room.join();
                return room;
            } catch (sabot.fleet.FleetException e) {
                if (System.nanoTime() - deadline > 0) {
                    throw e;
                }
                java.util.concurrent.locks.LockSupport.parkNanos(TimeUnit.MILLISECONDS.toNanos(50));
            }
        }
    }

    @Test
    void robotPublishesPresenceAndIdentityAndComesBackAfterAServerRestart() throws Exception {
        RobotSession session = startControlMl();
        assertNextEvent("online");
        assertTrue(session.isOnline());
        assertEquals(robot.toString(), session.jid());

        operatorLogsIn();
        Roster.getInstanceFor(operatorConnection).createItemAndRequestSubscription(robot, "robot", null);
        awaitPresence(Presence.Mode.available, "idle");
        assertIdentity(vCard());

        session.setPresence(PresenceLevel.BUSY, "mission running");
        awaitPresence(Presence.Mode.dnd, "mission running");

        XMPP.stopServer();
        assertNextEvent("offline");
        assertFalse(session.isOnline());
        assertTrue(session.connection() != null && !session.connection().isAuthenticated());

        XMPP.restart();
        assertNextEvent("online"); // by itself: nothing in the test asks it to reconnect
        robotPresences.clear();
        operatorLogsIn();
        awaitPresence(Presence.Mode.dnd, "mission running"); // the last presence set comes back
        assertIdentity(vCard());
        assertNull(events.poll(), "exactly one online per connection");
    }

    @Test
    void remoteFsTaskServesTheOperatorThroughTheSessionUntilItStops() throws Exception {
        startControlMl();
        assertNextEvent("online");
        Path root = Files.createDirectories(dir.resolve("fs-root"));
        Hashtable<String, Object> props = new Hashtable<>();
        props.put("root", root.toString());
        props.put("maxChunk", 1024);
        remotefs = service(ConfigurationAdmin.class).getConfiguration("sabot.task.remotefs", "?");
        remotefs.update(props);
        awaitTask("remotefs");

        operatorLogsIn();
        ControlMlManager wb = ControlMlManager.getInstanceFor(operatorConnection);
        EntityFullJid robotFull = JidCreate.entityFullFrom(robot + "/onboard");
        byte[] content = new byte[2500];
        new Random(20261121L).nextBytes(content);
        for (int offset = 0; offset < content.length; offset += 1024) {
            byte[] data = java.util.Arrays.copyOfRange(content, offset, Math.min(content.length, offset + 1024));
            var o = wb.set(robotFull, Resources.FS_WRITE, new FileChunk("maps/lab.bin", offset, data, FileChunk
                    .sha256Hex(data), offset + data.length == content.length));
            assertTrue(o.isSuccess(), o::toString);
        }
        assertArrayEquals(content, Files.readAllBytes(root.resolve("maps/lab.bin")));
        FileChunk first = wb.get(robotFull, Resources.FS_READ, new FileQuery("maps/lab.bin", 0, 0)).orElseThrow();
        assertEquals(1024, first.data().length, "the task's maxChunk applies");

        remotefs.delete();
        remotefs = null;
        awaitNoComponent("sabot.task.remotefs");
        // SCR may drop the component's configuration from its records before its deactivate (which removes the
        // handlers) has run: the robot stops serving cm.fs.* then, within the wait's deadline
        awaitCondition(() -> !wb.get(robotFull, Resources.FS_READ, new FileQuery("maps/lab.bin", 0, 0)).isSuccess(),
                "no cm.fs.* once the task stopped");
    }

    // ------------------------------------------------------------------------------------------ helpers

    <S> S service(Class<S> type) throws InterruptedException {
        ServiceTracker<S, S> t = new ServiceTracker<>(context, type, null);
        t.open();
        S s = t.waitForService(TimeUnit.SECONDS.toMillis(WAIT_S));
        assertNotNull(s, type.getSimpleName() + " not available within " + WAIT_S + " s");
        return s;
    }

    List<String> taskNames() {
        try {
            List<String> names = new java.util.ArrayList<>();
            for (org.osgi.framework.ServiceReference<OnboardTask> r : context.getServiceReferences(OnboardTask.class,
                    null)) {
                OnboardTask task = context.getService(r);
                if (task != null) { // null: unregistered since the references were listed
                    names.add(task.name());
                    context.ungetService(r);
                }
            }
            return names;
        } catch (org.osgi.framework.InvalidSyntaxException e) {
            throw new AssertionError(e);
        }
    }

    void awaitTask(String name) {
        awaitCondition(() -> taskNames().contains(name), "task " + name + " started");
    }

    void awaitNoComponent(String name) throws InterruptedException {
        org.osgi.service.component.runtime.ServiceComponentRuntime scr = service(
                org.osgi.service.component.runtime.ServiceComponentRuntime.class);
        awaitCondition(() -> scr.getComponentDescriptionDTOs().stream().filter(d -> d.name.equals(name))
                .allMatch(d -> scr.getComponentConfigurationDTOs(d).isEmpty()), name + " deactivated");
    }

    <S> void awaitNoService(Class<S> type) {
        awaitCondition(() -> context.getServiceReference(type) == null, type.getSimpleName() + " unregistered");
    }

    /** SCR (de)activates on its own thread after a configuration change: wait for the registry to show it. */
    static void awaitCondition(java.util.function.BooleanSupplier condition, String what) {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(WAIT_S);
        while (!condition.getAsBoolean()) {
            assertTrue(System.nanoTime() < deadline, what + " within " + WAIT_S + " s");
            // polls the service registry; parking instead of spinning leaves the CPU to SCR's thread
            java.util.concurrent.locks.LockSupport.parkNanos(TimeUnit.MILLISECONDS.toNanos(1));
        }
    }
}
