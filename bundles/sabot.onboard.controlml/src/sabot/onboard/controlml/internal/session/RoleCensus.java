package sabot.onboard.controlml.internal.session;

import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.TreeMap;

import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.RosterEntry;
import org.jivesoftware.smack.roster.RosterLoadedListener;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.AccessPolicy;
import sabot.controlml.Role;
import sabot.fleet.RosterEntriesListener;

/**
 * Logs who holds a role on this robot whenever that changes (its roster loaded or changed): the console then says
 * when a robot asking for access has been approved, or when a lab's last maintainer lost the role.
 */
final class RoleCensus extends RosterEntriesListener implements RosterLoadedListener {

    /** The session's logger: these are the session's console lines. */
    private static final Logger LOG = LoggerFactory.getLogger(ControlMlSession.class);

    private final Roster roster;
    private final AccessPolicy policy;
    private final String jid;
    private String last = "";

    RoleCensus(Roster roster, AccessPolicy policy, String jid) {
        this.roster = roster;
        this.policy = policy;
        this.jid = jid;
    }

    void listen() {
        roster.addRosterListener(this);
        roster.addRosterLoadedListener(this);
    }

    @Override
    public void onRosterLoaded(Roster loaded) {
        entriesChanged();
    }

    @Override
    public void onRosterLoadingFailed(Exception exception) {
        // the session's own handling says why it is offline
    }

    @Override
    protected synchronized void entriesChanged() {
        Map<Role, Integer> count = new TreeMap<>();
        for (RosterEntry e : roster.getEntries()) {
            Role r = policy.roleOf(e.getJid());
            if (r != Role.NONE) {
                count.merge(r, 1, Integer::sum);
            }
        }
        int total = count.values().stream().mapToInt(Integer::intValue).sum();
        List<String> each = new ArrayList<>();
        for (Role r : List.of(Role.MAINTAINER, Role.OPERATOR, Role.OBSERVER)) {
            if (count.containsKey(r)) {
                each.add(r.label() + " " + count.get(r));
            }
        }
        String text = total == 0 ? "accounts with a role on this robot: 0 (it obeys nobody: a robot asking for "
                + "access until the lab approves it, ./sabot enrol approve " + jid + ")"
                : "accounts with a role on this robot: " + total + " (" + String.join(", ", each) + ")";
        if (!text.equals(last)) {
            last = text;
            LOG.info(text);
        }
    }
}
