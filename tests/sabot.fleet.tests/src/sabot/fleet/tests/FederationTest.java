package sabot.fleet.tests;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.Arrays;
import java.util.Locale;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.packet.StanzaError.Condition;
import org.jivesoftware.smack.roster.AbstractPresenceEventListener;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.junit.jupiter.api.Tag;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.extension.RegisterExtension;
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.FullJid;
import org.jxmpp.jid.impl.JidCreate;

import sabot.controlml.AccessPolicy;
import sabot.controlml.ControlMlCondition;
import sabot.controlml.ControlMlError;
import sabot.controlml.ControlMlManager;
import sabot.controlml.Resources;
import sabot.controlml.Role;
import sabot.controlml.payload.Goal;
import sabot.fleet.AccessRules;
import sabot.fleet.SubscriptionGate;
import sabot.model.geometry.Pose2D;
import sabot.testsupport.xmpp.PrivateXmppServer;

/**
 * Two domains on two servers federated over s2s (docs/FEDERATION.md): Prosody serving sabot.local, ejabberd serving
 * sabot2.local, TLS with certificates of one lab CA between them. An operator of one domain sees and commands a robot
 * of the other under the roles granted on the robot's server (its groups may list accounts of the other domain); an
 * account of the other domain granted nothing is refused there, as a local stranger is.
 */
@Tag("ejabberd")
class FederationTest {

    static final long TIMEOUT_S = 10;
    /** The cross-domain get round trips measured per direction. */
    static final int REQUESTS = 200;

    @RegisterExtension
    static final PrivateXmppServer XMPP = PrivateXmppServer.federation();

    private static final String PASSWORD = "federation-pw";

    private static XMPPTCPConnection on(String localpart, String domain) throws Exception {
        XMPP.register(localpart, domain, PASSWORD);
        return XMPP.connect(XMPP.configuration(localpart, domain, PASSWORD).build());
    }

    @Test
    void anOperatorOnProsodyCommandsARobotOnEjabberd() throws Exception {
        crossDomain(PrivateXmppServer.SECOND_DOMAIN, PrivateXmppServer.DOMAIN, "to-ejabberd");
    }

    @Test
    void anOperatorOnEjabberdCommandsARobotOnProsody() throws Exception {
        crossDomain(PrivateXmppServer.DOMAIN, PrivateXmppServer.SECOND_DOMAIN, "to-prosody");
    }

    /**
     * A robot of {@code robotDomain}; an operator, an observer and a stranger of {@code otherDomain}. The lab grants
     * the roles on the robot's server, to the accounts of the other domain; the robot reads them in its roster.
     */
    private static void crossDomain(String robotDomain, String otherDomain, String name) throws Exception {
        XMPPTCPConnection robot = on(name + "-robot", robotDomain);
        XMPPTCPConnection operator = on(name + "-operator", otherDomain);
        XMPPTCPConnection observer = on(name + "-observer", otherDomain);
        XMPPTCPConnection stranger = on(name + "-stranger", otherDomain);
        AccessPolicy policy = AccessRules.labGroups().on(robot);
        Goal[] goal = FleetOnServerTest.goalDevice(robot, policy);
        SubscriptionGate.onDevice(robot, policy);
        Roster robotRoster = Roster.getInstanceFor(robot);
        // (listening from the start: ejabberd sends the robot's presence to an account granted a role on it at once,
        // as it does for a shared group's members)
        BareJid robotJid = robot.getUser().asBareJid();
        SubscriptionGate.onWorkbench(operator);
        Roster operatorRoster = Roster.getInstanceFor(operator);
        CountDownLatch seen = new CountDownLatch(1);
        operatorRoster.addPresenceEventListener(new AbstractPresenceEventListener() {
            @Override
            public void presenceAvailable(FullJid address, Presence p) {
                if (address.asBareJid().equals(robotJid)) {
                    seen.countDown();
                }
            }
        });

        XMPP.enrolRobot(robot.getUser().asBareJid());
        XMPP.grantOn(robotDomain, operator.getUser().asBareJid(), Role.OPERATOR);
        XMPP.grantOn(robotDomain, observer.getUser().asBareJid(), Role.OBSERVER);
        FleetOnServerTest.awaitRole(robotRoster, policy, operator, Role.OPERATOR);
        FleetOnServerTest.awaitRole(robotRoster, policy, observer, Role.OBSERVER);
        assertEquals(Role.NONE, policy.roleOf(stranger.getUser()), "a stranger of the other domain has a role");

        // the robot's presence across the domains: the operator asks for it, the robot's gate grants it (a role)
        operatorRoster.createItemAndRequestSubscription(robotJid, "robot", null);
        assertTrue(seen.await(TIMEOUT_S, TimeUnit.SECONDS), "the robot's presence never reached the operator on "
                + otherDomain + ": " + operatorRoster.getPresence(robotJid));

        // a goal and gets across the domains, under the robot's server's roles
        ControlMlManager cm = ControlMlManager.getInstanceFor(operator);
        Goal target = new Goal(new Pose2D(4, 2, 0), 0.1, 0.1);
        assertTrue(cm.set(robot.getUser(), Resources.GOAL, target).isSuccess(), "the operator's goal");
        assertEquals(target, goal[0]);
        long[] rtt = new long[REQUESTS];
        for (int i = 0; i < rtt.length; i++) {
            long t0 = System.nanoTime();
            assertEquals(target, cm.get(robot.getUser(), Resources.GOAL).orElseThrow());
            rtt[i] = System.nanoTime() - t0;
        }
        Arrays.sort(rtt);
        System.out.printf(Locale.ROOT, "[figure] federation: cm.goal get from %s to a robot on %s (s2s, TLS): p50 "
                + "%.2f ms, p99 %.2f ms (%d requests)%n", otherDomain, robotDomain, rtt[rtt.length / 2] / 1e6,
                rtt[rtt.length * 99 / 100] / 1e6, rtt.length);

        // the observer of the other domain reads, and may not set
        ControlMlManager observerCm = ControlMlManager.getInstanceFor(observer);
        assertEquals(target, observerCm.get(robot.getUser(), Resources.GOAL).orElseThrow());
        ControlMlError observerSet = observerCm.set(robot.getUser(), Resources.GOAL, new Goal(Pose2D.ORIGIN, 1, 1))
                .errorOrNull();
        assertNotNull(observerSet, "an observer's set was applied");
        assertEquals(ControlMlCondition.SET_NOT_PERMITTED, observerSet.cmCondition(), observerSet.toString());

        // the stranger of the other domain: not even a get
        ControlMlError strangerGet = ControlMlManager.getInstanceFor(stranger).get(robot.getUser(), Resources.GOAL)
                .errorOrNull();
        assertNotNull(strangerGet, "a stranger of the other domain read the robot");
        assertEquals(Condition.forbidden, strangerGet.condition());
        assertEquals(ControlMlCondition.ACCESS_DENIED, strangerGet.cmCondition());
        assertEquals(target, goal[0], "only the operator's goal");
    }

    /** Each server federates with the other domain only: a request to a third domain is refused by its own server. */
    @Test
    void aDomainBeyondThePairIsRefusedByTheSendersServer() throws Exception {
        for (String domain : new String[] { PrivateXmppServer.DOMAIN, PrivateXmppServer.SECOND_DOMAIN }) {
            XMPPTCPConnection operator = on("third-" + domain.replace('.', '-'), domain);
            EntityBareJid elsewhere = JidCreate.entityBareFrom("robot@sabot3.invalid");
            ControlMlError refused = ControlMlManager.getInstanceFor(operator).get(elsewhere, Resources.GOAL)
                    .errorOrNull();
            assertNotNull(refused, "a request to sabot3.invalid from " + domain + " was answered");
            System.out.printf(Locale.ROOT, "[federation] %s to sabot3.invalid: %s%n", domain, refused);
            assertTrue(refused.condition() != null, refused.toString());
        }
    }
}
