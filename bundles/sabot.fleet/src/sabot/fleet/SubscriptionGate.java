package sabot.fleet;

import java.time.Duration;
import java.util.Collection;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.roster.AbstractRosterListener;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.RosterListener;
import org.jivesoftware.smack.roster.SubscribeListener.SubscribeAnswer;
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.Jid;

import sabot.controlml.AccessPolicy;
import sabot.controlml.Role;

/**
 * Who may see a device's presence (and so its PEP telemetry). A device approves a subscription request from anyone
 * its access policy gives a role (at least observer), and subscribes back (its server must see the subscriber's presence and
 * entity caps to send PEP notifications); it denies everyone else. A workbench approves the subscriptions of the
 * devices it follows itself.
 */
public final class SubscriptionGate {

    private SubscriptionGate() {
    }

    /** Installs the device-side rule on a device's connection. */
    public static void onDevice(XMPPConnection device, AccessPolicy policy) {
        Roster.getInstanceFor(device).addSubscribeListener((from, request) -> policy.roleOf(from) != Role.NONE
                ? SubscribeAnswer.ApproveAndAlsoRequestIfRequired : SubscribeAnswer.Deny);
    }

    /**
     * How long a subscription request to a workbench waits for the roster push that adds its sender (see
     * {@link #inRoster}); a stranger's request is denied after it.
     */
    static final Duration ROSTER_PUSH_WAIT = Duration.ofSeconds(2);

    /** Installs the workbench-side rule: approve only entities in its roster (the devices it follows). */
    public static void onWorkbench(XMPPConnection workbench) {
        Roster roster = Roster.getInstanceFor(workbench);
        roster.addSubscribeListener((from, request) -> inRoster(roster, from.asBareJid()) ? SubscribeAnswer.Approve
                : SubscribeAnswer.Deny);
    }

    /**
     * Whether {@code jid} is in the roster, waiting up to {@link #ROSTER_PUSH_WAIT} for it to be added. A device
     * subscribes back as soon as it approves the workbench's request, and its request can overtake the roster push
     * that adds the device: Smack answers subscription requests on a pooled thread but applies roster pushes in order
     * on another. Denied then, the device never sees the workbench's presence, nor its caps, and sends it no PEP
     * notifications.
     */
    private static boolean inRoster(Roster roster, BareJid jid) {
        if (roster.getEntry(jid) != null) {
            return true;
        }
        CountDownLatch added = new CountDownLatch(1);
        RosterListener pushes = new AbstractRosterListener() {
            @Override
            public void entriesAdded(Collection<Jid> addresses) {
                if (addresses.contains(jid)) {
                    added.countDown();
                }
            }
        };
        roster.addRosterListener(pushes);
        try {
            if (roster.getEntry(jid) == null) {
                added.await(ROSTER_PUSH_WAIT.toMillis(), TimeUnit.MILLISECONDS);
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        } finally {
            roster.removeRosterListener(pushes);
        }
        return roster.getEntry(jid) != null;
    }
}
