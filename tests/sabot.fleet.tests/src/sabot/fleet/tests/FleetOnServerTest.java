package sabot.fleet.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.IOException;
import java.lang.reflect.Field;
import java.net.InetAddress;
import java.net.Socket;
import java.net.URI;
import java.time.LocalDate;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.XMPPException;
import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.roster.AbstractPresenceEventListener;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.RosterGroup;
import org.jivesoftware.smack.sasl.SASLErrorException;
import org.jivesoftware.smackx.iqregister.AccountManager;
import org.jivesoftware.smack.packet.StanzaError.Condition;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.Test;
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.FullJid;
import org.jxmpp.jid.impl.JidCreate;
import org.jxmpp.jid.parts.Localpart;

import sabot.controlml.AccessPolicy;
import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.PresenceLevel;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.payload.Goal;
import sabot.controlml.payload.MotorGains;
import sabot.controlml.payload.PidGains;
import sabot.controlml.payload.MissionState;
import sabot.fleet.AccessRules;
import sabot.fleet.Enrolment;
import sabot.fleet.FleetConnections;
import sabot.fleet.FleetLobby;
import sabot.fleet.PresenceAnnouncer;
import sabot.fleet.PresenceLevels;
import sabot.fleet.RosterCompiler;
import sabot.fleet.RosterEntriesListener;
import sabot.fleet.SubscriptionGate;
import sabot.identity.DeviceIdentityManager;
import sabot.identity.DeviceProfile;
import sabot.identity.DeviceUrn;
import sabot.identity.Inventory;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.xmpp.PrivateXmppServer;

/** Fleet rules on a real server: registration, presence levels, roster rules 11 and 12, authorization. */
abstract class FleetOnServerTest {

    static final long TIMEOUT_S = 10;

    protected abstract PrivateXmppServer server();

    /** In-band registration is closed: an unknown device cannot make itself an account (docs/SECURITY.md). */
    @Test
    void noDeviceRegistersItself() throws Exception {
        XMPPTCPConnection anonymous = new XMPPTCPConnection(server().configuration("robot-reg",
                PrivateXmppServer.DOMAIN, "pw").build());
        try {
            anonymous.connect();
            AccountManager accounts = AccountManager.getInstance(anonymous);
            XMPPException.XMPPErrorException refused = assertThrows(XMPPException.XMPPErrorException.class,
                    () -> accounts.createAccount(Localpart.from("robot-reg"), "pw"));
            assertTrue(Set.of(Condition.not_allowed, Condition.forbidden, Condition.service_unavailable,
                    Condition.feature_not_implemented).contains(refused.getStanzaError().getCondition()), refused
                            .toString());
        } finally {
            anonymous.disconnect();
        }
        assertThrows(SASLErrorException.class, () -> server().connect(server().configuration("robot-reg",
                PrivateXmppServer.DOMAIN, "pw").build()), "an account was made");
    }

    /**
     * A robot enrolled with a token (docs/SECURITY.md, "Enrolment"): the token logs in once, then the robot's own
     * password replaces it; until the lab approves, the robot sees no group, so an operator of the lab has no role
     * on it and is refused, while the operator sees it asking for access; approved, it obeys; a robot refused loses
     * its account.
     */
    @Test
    void anEnrolledRobotObeysNobodyUntilApprovedAndItsTokenLogsInOnce() throws Exception {
        XMPPTCPConnection operator = server().login("enrol-operator");
        server().grant(operator.getUser().asBareJid(), Role.OPERATOR);
        EntityBareJid robotJid = JidCreate.entityBareFrom("enrol-robot@" + PrivateXmppServer.DOMAIN);
        String token = server().enrolToken(robotJid);
        assertTrue(Enrolment.isToken(token), token);

        XMPPTCPConnection robot = server().connect(server().configuration("enrol-robot", PrivateXmppServer.DOMAIN,
                token).build());
        String own = Enrolment.newPassword();
        Enrolment.replaceToken(robot, own);
        assertThrows(SASLErrorException.class, () -> server().connect(server().configuration("enrol-robot",
                PrivateXmppServer.DOMAIN, token).setResource("check").build()), "the token logged in twice");
        server().connect(server().configuration("enrol-robot", PrivateXmppServer.DOMAIN, own).setResource("check")
                .build()).disconnect(); // (another resource: the same would replace the robot's session)

        Roster roster = Roster.getInstanceFor(robot);
        roster.reloadAndWait();
        AccessPolicy policy = AccessRules.labGroups().on(robot);
        Goal[] goal = goalDevice(robot, policy);
        // the operator sees it asking for access; the robot sees no group, so nobody has a role there
        Roster operators = Roster.getInstanceFor(operator);
        awaitRole(operators, j -> AccessRules.groupsIn(operators, j).contains(AccessRules.ENROLLING_GROUP)
                ? Role.OBSERVER : Role.NONE, robot, Role.OBSERVER);
        assertEquals(List.of(), roster.getGroups().stream().map(RosterGroup::getName).toList(),
                "a robot asking for access sees a group");
        assertEquals(Role.NONE, policy.roleOf(operator.getUser()));
        Goal target = new Goal(new Pose2D(2, 1, 0), 0.1, 0.1);
        var refused = ControlMlManager.getInstanceFor(operator).set(robot.getUser(), Resources.GOAL, target).errorOrNull();
        assertEquals(ControlMlCondition.ACCESS_DENIED, refused.cmCondition(), String.valueOf(refused));
        assertEquals(Pose2D.ORIGIN, goal[0].pose(), "a refused goal changed the robot");

        long t0 = System.nanoTime();
        server().approve(robotJid);
        awaitRole(roster, policy, operator, Role.OPERATOR);
        System.out.printf(Locale.ROOT, "[figure] %s: approval (sabot-xmpp enrol approve) to the operator's role on "
                + "the running robot: %d ms%n", server().kind(), TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - t0));
        assertTrue(ControlMlManager.getInstanceFor(operator).set(robot.getUser(), Resources.GOAL, target).isSuccess());
        assertEquals(target, goal[0]);
        awaitRole(operators, j -> AccessRules.groupsIn(operators, j).contains(AccessRules.ROBOTS_GROUP)
                ? Role.OBSERVER : Role.NONE, robot, Role.OBSERVER);

        // another robot, refused: its account is gone
        EntityBareJid otherJid = JidCreate.entityBareFrom("enrol-other@" + PrivateXmppServer.DOMAIN);
        String otherToken = server().enrolToken(otherJid);
        IOException twice = assertThrows(IOException.class, () -> server().enrolToken(otherJid));
        assertTrue(twice.getMessage().contains("already an account"), twice.getMessage());
        IOException notAsking = assertThrows(IOException.class, () -> server().approve(robotJid));
        assertTrue(notAsking.getMessage().contains("is not asking for access"), notAsking.getMessage());
        server().refuse(otherJid);
        assertThrows(SASLErrorException.class, () -> server().connect(server().configuration("enrol-other",
                PrivateXmppServer.DOMAIN, otherToken).build()), "a refused robot logged in");
    }

    @Test
    void productionConnectionsUseTcpNoDelayAndStreamManagement() throws Exception {
        server().register("robot-nd", PrivateXmppServer.DOMAIN, "pw");
        XMPPTCPConnection c = server().connect(FleetConnections.builder(PrivateXmppServer.DOMAIN, InetAddress
                .getLoopbackAddress(), server().port(), server().trust()).setUsernameAndPassword("robot-nd",
                        "pw").build());
        Field f = XMPPTCPConnection.class.getDeclaredField("socket");
        f.setAccessible(true);
        assertTrue(((Socket) f.get(c)).getTcpNoDelay());
        assertTrue(c.isSmEnabled());
    }

    @Test
    void presenceLevelChangesAreSeenByASubscriber() throws Exception {
        XMPPTCPConnection robot = server().login("robot-pl");
        XMPPTCPConnection wb = server().login("wb-pl");
        AccessPolicy policy = AccessRules.none().withJid(Role.MAINTAINER, wb.getUser().asBareJid()).on(robot);
        SubscriptionGate.onDevice(robot, policy);
        SubscriptionGate.onWorkbench(wb);
        BlockingQueue<PresenceLevel> seen = new LinkedBlockingQueue<>();
        Roster.getInstanceFor(wb).addPresenceEventListener(new AbstractPresenceEventListener() {
            @Override
            public void presenceAvailable(FullJid address, Presence p) {
                if (address.asBareJid().equals(robot.getUser().asBareJid())) {
                    seen.add(PresenceLevels.of(p));
                }
            }
        });
        PresenceAnnouncer announcer = new PresenceAnnouncer(robot);
        announcer.announce();
        Roster.getInstanceFor(wb).createItemAndRequestSubscription(robot.getUser().asEntityBareJid(), "robot", null);

        assertEquals(PresenceLevel.FREE, seen.poll(TIMEOUT_S, TimeUnit.SECONDS));
        assertTrue(announcer.missionChanged(MissionState.RUNNING));
        assertEquals(PresenceLevel.BUSY, next(seen, PresenceLevel.FREE));
        assertTrue(announcer.maintenanceChanged(true));
        assertEquals(PresenceLevel.AWAY, next(seen, PresenceLevel.BUSY));
        assertTrue(announcer.maintenanceChanged(false));
        assertEquals(PresenceLevel.BUSY, next(seen, PresenceLevel.AWAY), "back to the mission");
        assertTrue(announcer.missionChanged(MissionState.DONE));
        assertEquals(PresenceLevel.FREE, next(seen, PresenceLevel.BUSY));
        assertTrue(!announcer.missionChanged(MissionState.DONE), "no change, no presence");
        assertEquals(Presence.Mode.available, Roster.getInstanceFor(wb).getPresence(robot.getUser().asBareJid())
                .getMode());
    }

    /**
     * The next level that differs from the previous one: a server may repeat the current presence once more after
     * the subscription (Prosody answers its own probe).
     */
    private static PresenceLevel next(BlockingQueue<PresenceLevel> seen, PresenceLevel previous)
            throws InterruptedException {
        while (true) {
            PresenceLevel l = seen.poll(TIMEOUT_S, TimeUnit.SECONDS);
            assertNotNull(l, "no presence after " + previous);
            if (l != previous) {
                return l;
            }
        }
    }

    private XMPPTCPConnection device(String name, String domain, String manufacturer, String role,
            Set<String> readerDomains) throws Exception {
        XMPPTCPConnection c = server().login(name, domain);
        SubscriptionGate.onDevice(c, AccessRules.none().withDomains(Role.OBSERVER, readerDomains).on(c));
        if (manufacturer != null) {
            DeviceProfile p = new DeviceProfile("mobile robot", manufacturer, "R2", name, URI.create("http://" + name
                    + ".lab.example/"), 45.764043, 4.835659, DeviceUrn.urnOf("SN-" + name), c.getUser()
                            .asBareJid().toString(), role, LocalDate.of(2026, 11, 21), null, null);
            Inventory inv = new Inventory(1, p.uid(), new Inventory.Mechanic("chassis", List.of()), List.of(
                    new Inventory.Board("pc", "x86_64", null, List.of(), List.of(new Inventory.Item("sabot.onboard",
                            "0.1.0")), List.of())), List.of());
            DeviceIdentityManager.getInstanceFor(c).publish(p, inv).orElseThrow();
        }
        return c;
    }

    /**
     * A lobby impostor: an account whose own vCard says it is one of the lab's robots. A workbench that asks the
     * server (its robots' shared group) does not follow it; the robot the server vouches for is in its roster already.
     */
    @Test
    void anOccupantWhoseOwnVCardSaysRobotIsNotFollowedWithoutTheServersWord() throws Exception {
        Set<String> lab = Set.of(PrivateXmppServer.DOMAIN);
        EntityBareJid lobbyRoom = JidCreate.entityBareFrom("fleet-imp@conference." + PrivateXmppServer.DOMAIN);
        XMPPTCPConnection robot = device("imp-robot", PrivateXmppServer.DOMAIN, "Sabot Robotics", "robot", lab);
        XMPPTCPConnection impostor = device("imp-impostor", PrivateXmppServer.DOMAIN, "Sabot Robotics", "robot", lab);
        XMPPTCPConnection wb = server().login("imp-wb");
        server().enrolRobot(robot.getUser().asBareJid());
        server().grant(wb.getUser().asBareJid(), Role.OBSERVER); // ejabberd shows a group to the groups' members
        Roster roster = Roster.getInstanceFor(wb);
        // (the robot's entry in the robots' group, seen through a policy that says so)
        awaitRole(roster, j -> AccessRules.groupsIn(roster, j).contains(AccessRules.ROBOTS_GROUP) ? Role.OBSERVER
                : Role.NONE, robot, Role.OBSERVER);
        for (XMPPTCPConnection d : List.of(robot, impostor)) {
            new FleetLobby(d, lobbyRoom).join();
        }
        FleetLobby lobby = new FleetLobby(wb, lobbyRoom);
        lobby.join();

        RosterCompiler.Report report = new RosterCompiler(wb, lobby, new RosterCompiler.Rules(RosterCompiler.Rules
                .manufacturerAndRole("Sabot Robotics", "robot"), jid -> AccessRules.groupsIn(roster, jid).contains(
                        AccessRules.ROBOTS_GROUP), Set.of(), "fleet")).compile();

        assertEquals(List.of(), report.subscribed());
        assertEquals("not vouched for (its own vCard is not proof)", report.rejected().get(impostor.getUser()
                .asEntityBareJid()));
        assertTrue(roster.getEntry(impostor.getUser().asBareJid()) == null, "the impostor is in the roster");
        assertTrue(AccessRules.groupsIn(roster, robot.getUser()).contains(AccessRules.ROBOTS_GROUP));
    }

    @Test
    void rosterCompilationSubscribesMatchingOnlineDevicesAndTheListedForeignOnes() throws Exception {
        Set<String> lab = Set.of(PrivateXmppServer.DOMAIN, PrivateXmppServer.SECOND_DOMAIN);
        EntityBareJid lobbyRoom = JidCreate.entityBareFrom("fleet-rc@conference." + PrivateXmppServer.DOMAIN);
        XMPPTCPConnection a = device("rc-a", PrivateXmppServer.DOMAIN, "Sabot Robotics", "robot", lab);
        XMPPTCPConnection b = device("rc-b", PrivateXmppServer.DOMAIN, "Sabot Robotics", "robot", lab);
        XMPPTCPConnection other = device("rc-other", PrivateXmppServer.DOMAIN, "Other Corp", "robot", lab);
        XMPPTCPConnection noCard = device("rc-nocard", PrivateXmppServer.DOMAIN, null, null, lab);
        XMPPTCPConnection foreign = device("rc-foreign", PrivateXmppServer.SECOND_DOMAIN, "Other Corp", "sensor", lab);
        for (XMPPTCPConnection d : List.of(a, b, other, noCard)) {
            new FleetLobby(d, lobbyRoom).join();
        }
        XMPPTCPConnection wb = server().login("rc-wb");
        SubscriptionGate.onWorkbench(wb);
        Map<BareJid, CountDownLatch> online = new ConcurrentHashMap<>();
        for (XMPPTCPConnection d : List.of(a, b, foreign)) {
            online.put(d.getUser().asBareJid(), new CountDownLatch(1));
        }
        Roster.getInstanceFor(wb).addPresenceEventListener(new AbstractPresenceEventListener() {
            @Override
            public void presenceAvailable(FullJid address, Presence p) {
                CountDownLatch l = online.get(address.asBareJid());
                if (l != null) {
                    l.countDown();
                }
            }
        });
        FleetLobby lobby = new FleetLobby(wb, lobbyRoom);
        lobby.join();

        RosterCompiler.Report report = new RosterCompiler(wb, lobby, new RosterCompiler.Rules(RosterCompiler.Rules
                .manufacturerAndRole("Sabot Robotics", "robot"), Set.of(foreign.getUser().asEntityBareJid()),
                "fleet")).compile();

        assertEquals(Set.of(a.getUser().asEntityBareJid(), b.getUser().asEntityBareJid()), Set.copyOf(report
                .subscribed()));
        assertEquals(List.of(foreign.getUser().asEntityBareJid()), report.foreign());
        assertTrue(report.rejected().get(other.getUser().asEntityBareJid()).contains("Other Corp"), report
                .rejected().toString());
        assertTrue(report.rejected().get(noCard.getUser().asEntityBareJid()).startsWith("NO_VCARD"), report
                .rejected().toString());
        for (var e : online.entrySet()) {
            assertTrue(e.getValue().await(TIMEOUT_S, TimeUnit.SECONDS), "no presence of " + e.getKey());
        }
        Roster roster = Roster.getInstanceFor(wb);
        assertEquals(3, roster.getGroup("fleet").getEntryCount());
        assertTrue(roster.getEntry(other.getUser().asBareJid()) == null);
    }

    /**
     * Roles as a lab grants them: the server's shared groups ({@code sabot-xmpp group add|remove}), which the server
     * writes into the device's roster; the device reads them at each request. Granted and revoked while everyone is
     * online: the change reaches the running device by the server's roster push.
     */
    @Test
    void rolesAreTheServersSharedGroupsAndAChangeReachesARunningDevice() throws Exception {
        XMPPTCPConnection robot = server().login("robot-roles");
        XMPPTCPConnection observer = server().login("wb-observer");
        XMPPTCPConnection operator = server().login("wb-operator");
        XMPPTCPConnection maintainer = server().login("wb-maintainer");
        XMPPTCPConnection stranger = server().login("wb-stranger");
        Roster roster = Roster.getInstanceFor(robot);
        AccessRules rules = AccessRules.labGroups();
        AccessPolicy policy = rules.on(robot);
        ControlMlManager cm = ControlMlManager.getInstanceFor(robot);
        cm.setAccessPolicy(policy);
        Goal[] goal = { new Goal(Pose2D.ORIGIN, 0.1, 0.1) };
        PidGains[] gains = { new PidGains(List.of(new MotorGains(0, 1, 0, 0))) };
        cm.onSet(Resources.GOAL, (r, g) -> {
            goal[0] = g;
            return Outcome.done();
        });
        cm.onGet(Resources.GOAL, (r, q) -> Outcome.success(goal[0]));
        cm.onSet(Resources.PID, (r, g) -> {
            gains[0] = g;
            return Outcome.done();
        });
        assertEquals(Role.NONE, policy.roleOf(operator.getUser()), "a role before any grant");

        long t0 = System.nanoTime();
        server().enrolRobot(robot.getUser().asBareJid());
        server().grant(observer.getUser().asBareJid(), Role.OBSERVER);
        server().grant(operator.getUser().asBareJid(), Role.OPERATOR);
        server().grant(maintainer.getUser().asBareJid(), Role.MAINTAINER);
        awaitRole(roster, policy, maintainer, Role.MAINTAINER);
        awaitRole(roster, policy, operator, Role.OPERATOR);
        awaitRole(roster, policy, observer, Role.OBSERVER);
        System.out.printf(Locale.ROOT, "[figure] %s: four grants (sabot-xmpp group add) to roles on the "
                + "running device: %d ms%n", server().kind(), TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - t0));

        // in two groups: the higher role; out of one of them, the other's (ejabberd pushes the item with the one
        // group that changed, or its removal: the device reloads its roster to see the item whole)
        server().grant(observer.getUser().asBareJid(), Role.MAINTAINER);
        awaitRole(roster, policy, observer, Role.MAINTAINER);
        server().revoke(observer.getUser().asBareJid(), Role.MAINTAINER);
        awaitRole(roster, policy, observer, Role.OBSERVER);

        Goal target = new Goal(new Pose2D(3, 4, 0), 0.1, 0.1);
        PidGains newGains = new PidGains(List.of(new MotorGains(0, 7, 1, 0)));
        // observer: gets; no set
        assertEquals(goal[0], ControlMlManager.getInstanceFor(observer).get(robot.getUser(), Resources.GOAL)
                .orElseThrow());
        var observerSet = ControlMlManager.getInstanceFor(observer).set(robot.getUser(), Resources.GOAL, target)
                .errorOrNull();
        assertEquals(Condition.forbidden, observerSet.condition());
        assertEquals(ControlMlCondition.SET_NOT_PERMITTED, observerSet.cmCondition());
        assertTrue(observerSet.text().contains("is an observer on this device; a set of cm.goal needs the operator "
                + "role"), observerSet.text());
        // operator: goals; not the gains
        assertTrue(ControlMlManager.getInstanceFor(operator).set(robot.getUser(), Resources.GOAL, target)
                .isSuccess());
        var operatorPid = ControlMlManager.getInstanceFor(operator).set(robot.getUser(), Resources.PID, newGains)
                .errorOrNull();
        assertEquals(ControlMlCondition.SET_NOT_PERMITTED, operatorPid.cmCondition());
        assertTrue(operatorPid.text().contains("a set of cm.pid needs the maintainer role"), operatorPid.text());
        // maintainer: the gains too
        assertTrue(ControlMlManager.getInstanceFor(maintainer).set(robot.getUser(), Resources.PID, newGains)
                .isSuccess());
        // a stranger: not even a get
        var strangerGet = ControlMlManager.getInstanceFor(stranger).get(robot.getUser(), Resources.GOAL)
                .errorOrNull();
        assertEquals(Condition.forbidden, strangerGet.condition());
        assertEquals(ControlMlCondition.ACCESS_DENIED, strangerGet.cmCondition());
        assertEquals(target, goal[0], "only the operator's goal");
        assertEquals(newGains, gains[0], "only the maintainer's gains");

        // revoked while online: the operator's next goal is refused
        long t1 = System.nanoTime();
        server().revoke(operator.getUser().asBareJid(), Role.OPERATOR);
        awaitRole(roster, policy, operator, Role.NONE);
        System.out.printf(Locale.ROOT, "[figure] %s: revocation to no role on the running device: %d ms%n",
                server().kind(), TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - t1));
        var revoked = ControlMlManager.getInstanceFor(operator).set(robot.getUser(), Resources.GOAL, new Goal(
                Pose2D.ORIGIN, 1, 1)).errorOrNull();
        assertEquals(ControlMlCondition.ACCESS_DENIED, revoked.cmCondition());
        assertEquals(target, goal[0], "the refused set changed nothing");
    }

    /**
     * Makes {@code robot} a device that serves {@code cm.goal} (get and set) under {@code policy}.
     *
     * @return the goal it holds (one element, the handlers' own), at first the origin
     */
    static Goal[] goalDevice(XMPPConnection robot, AccessPolicy policy) {
        ControlMlManager cm = ControlMlManager.getInstanceFor(robot);
        cm.setAccessPolicy(policy);
        Goal[] goal = { new Goal(Pose2D.ORIGIN, 0.1, 0.1) };
        cm.onGet(Resources.GOAL, (r, q) -> Outcome.success(goal[0]));
        cm.onSet(Resources.GOAL, (r, g) -> {
            goal[0] = g;
            return Outcome.done();
        });
        return goal;
    }

    /** Waits, on the device's roster changes, until {@code who} holds {@code role} there (at most 10 s). */
    static void awaitRole(Roster roster, AccessPolicy policy, XMPPConnection who, Role role)
            throws InterruptedException {
        Object changed = new Object();
        var listener = new RosterEntriesListener() {
            @Override
            protected void entriesChanged() {
                synchronized (changed) {
                    changed.notifyAll();
                }
            }
        };
        roster.addRosterListener(listener);
        try {
            long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(TIMEOUT_S);
            synchronized (changed) {
                while (policy.roleOf(who.getUser()) != role) {
                    long left = deadline - System.nanoTime();
                    assertTrue(left > 0, who.getUser().asBareJid() + " is not " + role.withArticle() + " on the device "
                            + "after " + TIMEOUT_S + " s (its groups there: " + AccessRules.groupsIn(roster, who
                                    .getUser()) + ")");
                    changed.wait(Math.max(1, TimeUnit.NANOSECONDS.toMillis(left)));
                }
            }
        } finally {
            roster.removeRosterListener(listener);
        }
    }
}
