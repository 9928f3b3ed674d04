package sabot.system;

import java.util.ArrayList;
import java.util.Collection;
import java.util.List;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.function.Predicate;

import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.roster.AbstractRosterListener;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.RosterEntry;
import org.jivesoftware.smack.tcp.XMPPTCPConnection;
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.Jid;

/**
 * The robot's presence as an operator's client sees it: the operator subscribes (the robot approves operators) and
 * every presence the robot sends is kept, so a test waits for the one it expects instead of sleeping.
 */
final class PresenceWatch {

    private final List<Presence> seen = new ArrayList<>();

    private PresenceWatch() {
    }

    /** Subscribes {@code operator} to {@code robot}'s presence and waits until the robot approved. */
    static PresenceWatch subscribe(XMPPTCPConnection operator, BareJid robot) throws Exception {
        PresenceWatch watch = new PresenceWatch();
        Roster roster = Roster.getInstanceFor(operator);
        CountDownLatch approved = new CountDownLatch(1);
        roster.addRosterListener(new AbstractRosterListener() {
            @Override
            public void entriesUpdated(Collection<Jid> addresses) {
                RosterEntry e = roster.getEntry(robot);
                if (e != null && e.canSeeHisPresence()) {
                    approved.countDown();
                }
            }

            @Override
            public void presenceChanged(Presence presence) {
                if (presence.getFrom().asBareJid().equals(robot)) {
                    synchronized (watch.seen) {
                        watch.seen.add(presence);
                        watch.seen.notifyAll();
                    }
                }
            }
        });
        roster.createItemAndRequestSubscription(robot, "robot", null);
        if (!approved.await(10, TimeUnit.SECONDS)) {
            throw new AssertionError("the robot did not approve the operator's presence subscription");
        }
        return watch;
    }

    /** Waits for a presence of the robot matching {@code p} (one already received counts). */
    Presence await(Predicate<Presence> p, String what) throws InterruptedException {
        return awaitAfter(null, p, what);
    }

    /**
     * Waits for a presence of the robot matching {@code p} received after {@code earlier} (null: any received), e.g.
     * Free again after Away.
     */
    Presence awaitAfter(Presence earlier, Predicate<Presence> p, String what) throws InterruptedException {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(20);
        synchronized (seen) {
            while (true) {
                int from = earlier == null ? 0 : seen.indexOf(earlier) + 1;
                for (Presence presence : seen.subList(from, seen.size())) {
                    if (p.test(presence)) {
                        return presence;
                    }
                }
                long left = deadline - System.nanoTime();
                if (left <= 0) {
                    throw new AssertionError("no presence " + what + "; seen: " + seen);
                }
                TimeUnit.NANOSECONDS.timedWait(seen, left);
            }
        }
    }
}
