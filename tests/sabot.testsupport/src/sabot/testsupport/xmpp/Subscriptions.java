package sabot.testsupport.xmpp;

import java.time.Duration;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.roster.AbstractPresenceEventListener;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.SubscribeListener.SubscribeAnswer;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.FullJid;
import org.jxmpp.jid.Jid;

/** Roster set-up for tests, done the way the fleet does it on real servers. */
public final class Subscriptions {

    private Subscriptions() {
    }

    /**
     * Mutual presence subscription as a workbench and a robot make it: the workbench asks, the robot approves and
     * asks back. Returns when each has received the other's available presence — the robot's server needs the
     * workbench's presence, with its entity caps ({@code +notify}), before it sends PEP notifications. (Both sides
     * asking at once made ejabberd's PEP delivery unreliable.)
     *
     * @throws AssertionError when either presence has not arrived within {@code timeout}
     */
    public static void mutual(XMPPTCPConnection workbench, XMPPTCPConnection robot, Duration timeout)
            throws Exception {
        Roster robotRoster = Roster.getInstanceFor(robot);
        robotRoster.addSubscribeListener((from, request) -> SubscribeAnswer.ApproveAndAlsoRequestIfRequired);
        Roster wbRoster = Roster.getInstanceFor(workbench);
        wbRoster.setSubscriptionMode(Roster.SubscriptionMode.accept_all);
        EntityBareJid robotJid = robot.getUser().asEntityBareJid();
        CountDownLatch robotSeen = presenceSeen(wbRoster, robotJid);
        CountDownLatch workbenchSeen = presenceSeen(robotRoster, workbench.getUser().asEntityBareJid());
        wbRoster.createItemAndRequestSubscription(robotJid, robotJid.getLocalpart().toString(), null);
        if (!robotSeen.await(timeout.toMillis(), TimeUnit.MILLISECONDS)) {
            throw new AssertionError("the workbench does not see " + robotJid + " within " + timeout);
        }
        if (!workbenchSeen.await(timeout.toMillis(), TimeUnit.MILLISECONDS)) {
            throw new AssertionError("the robot does not see " + workbench.getUser() + " within " + timeout);
        }
    }

    private static CountDownLatch presenceSeen(Roster roster, Jid who) {
        CountDownLatch seen = new CountDownLatch(1);
        roster.addPresenceEventListener(new AbstractPresenceEventListener() {
            @Override
            public void presenceAvailable(FullJid address, org.jivesoftware.smack.packet.Presence presence) {
                if (who.equals(address.asEntityBareJidIfPossible())) {
                    seen.countDown();
                }
            }
        });
        return seen;
    }
}
