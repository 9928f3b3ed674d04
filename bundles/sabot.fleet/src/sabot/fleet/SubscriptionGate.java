package sabot.fleet;

import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.RosterEntry;
import org.jivesoftware.smack.roster.SubscribeListener.SubscribeAnswer;

import sabot.controlml.AccessLevel;
import sabot.controlml.AccessPolicy;

/**
 * Who may see a device's presence (and so its PEP telemetry). A device approves a subscription request from anyone
 * its access policy lets at least {@code get}, and subscribes back (its server must see the subscriber's presence and
 * entity caps to send PEP notifications); it denies everyone else. A workbench approves the subscriptions of the
 * devices it follows itself.
 */
public final class SubscriptionGate {

    private SubscriptionGate() {
    }

    /** Installs the device-side rule on a device's connection. */
    public static void onDevice(XMPPConnection device, AccessPolicy policy) {
        Roster.getInstanceFor(device).addSubscribeListener((from, request) -> policy.levelOf(from) != AccessLevel.NONE
                ? SubscribeAnswer.ApproveAndAlsoRequestIfRequired : SubscribeAnswer.Deny);
    }

    /** Installs the workbench-side rule: approve only entities already in its roster (the devices it follows). */
    public static void onWorkbench(XMPPConnection workbench) {
        Roster roster = Roster.getInstanceFor(workbench);
        roster.addSubscribeListener((from, request) -> {
            RosterEntry e = roster.getEntry(from.asBareJid());
            return e != null ? SubscribeAnswer.Approve : SubscribeAnswer.Deny;
        });
    }
}
