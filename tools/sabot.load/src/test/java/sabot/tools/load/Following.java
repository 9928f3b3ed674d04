package sabot.tools.load;

import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Duration;
import java.util.Collection;
import java.util.List;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.packet.StanzaError;
import org.jivesoftware.smack.roster.AbstractRosterListener;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.RosterEntry;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.Jid;

import sabot.controlml.ControlMlManager;
import sabot.controlml.Outcome;
import sabot.controlml.Resources;

/**
 * An operator's client follows load robots as the workbench does (ControlMlFleet): a presence subscription the robot
 * approves (and asks back, which {@code SubscriptionGate.onWorkbench} approves), then an explicit XEP-0060 subscription
 * to the robot's position node besides the caps' {@code +notify}, which neither ejabberd 23.01 nor, more rarely,
 * Prosody 0.12 always honours for a new contact (both tests here once had no telemetry from any robot in 30 s).
 */
public final class Following {

    private static final Duration WAIT = Duration.ofSeconds(30);

    private Following() {
    }

    /** Subscribes the logged-in {@code operator} to each robot, waits for every approval and follows each robot. */
    public static void follow(XMPPTCPConnection operator, List<EntityBareJid> robots) throws Exception {
        Roster roster = Roster.getInstanceFor(operator);
        Set<BareJid> approved = ConcurrentHashMap.newKeySet();
        CountDownLatch all = new CountDownLatch(robots.size());
        roster.addRosterListener(new AbstractRosterListener() {
            @Override
            public void entriesAdded(Collection<Jid> addresses) {
                entriesUpdated(addresses);
            }

            @Override
            public void entriesUpdated(Collection<Jid> addresses) {
                for (Jid a : addresses) {
                    RosterEntry e = roster.getEntry(a.asBareJid());
                    if (e != null && e.canSeeHisPresence() && approved.add(a.asBareJid())) {
                        all.countDown();
                    }
                }
            }
        });
        for (EntityBareJid r : robots) {
            roster.createItemAndRequestSubscription(r, r.getLocalpart().toString(), null);
        }
        assertTrue(all.await(WAIT.toSeconds(), TimeUnit.SECONDS), "robots that approved: " + approved);
        ControlMlManager cm = ControlMlManager.getInstanceFor(operator);
        for (EntityBareJid r : robots) {
            Outcome<Void> followed = followWhenPublished(cm, r);
            assertTrue(followed.isSuccess(), r + ": " + followed.errorOrNull());
        }
    }

    /**
     * Follows the robot's position node; the node exists from the robot's first publication on (the load publishes
     * from its login), so {@code item-not-found} is asked again, each time a round trip, for 10 s at most.
     */
    private static Outcome<Void> followWhenPublished(ControlMlManager cm, EntityBareJid robot) {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(10);
        Outcome<Void> o = cm.telemetry().follow(robot, Resources.POSITION);
        while (!o.isSuccess() && o.errorOrNull().condition() == StanzaError.Condition.item_not_found
                && System.nanoTime() < deadline) {
            o = cm.telemetry().follow(robot, Resources.POSITION);
        }
        return o;
    }
}
