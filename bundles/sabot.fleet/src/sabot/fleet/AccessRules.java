package sabot.fleet;

import java.util.Objects;
import java.util.Set;

import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.RosterEntry;
import org.jivesoftware.smack.roster.RosterGroup;
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.Jid;

import sabot.controlml.AccessLevel;
import sabot.controlml.AccessPolicy;

/**
 * Who may command a device: configured workbench JIDs or members of configured roster groups may {@code set}; other
 * configured JIDs, groups or whole domains may only {@code get}; everyone else is answered {@code forbidden}.
 * Group membership is read from the device's roster at each request, so moving a workbench between groups takes
 * effect at once.
 *
 * @param setters      bare JIDs that may set (and get)
 * @param setterGroups roster groups whose members may set
 * @param getters      bare JIDs that may get
 * @param getterGroups roster groups whose members may get
 * @param getterDomains domains whose accounts may get (e.g. the lab's own domain)
 */
public record AccessRules(Set<BareJid> setters, Set<String> setterGroups, Set<BareJid> getters,
        Set<String> getterGroups, Set<String> getterDomains) {

    public AccessRules {
        setters = Set.copyOf(setters);
        setterGroups = Set.copyOf(setterGroups);
        getters = Set.copyOf(getters);
        getterGroups = Set.copyOf(getterGroups);
        getterDomains = Set.copyOf(getterDomains);
    }

    /** @return the policy these rules define on a device's connection (its roster supplies the groups) */
    public AccessPolicy on(XMPPConnection device) {
        Roster roster = Roster.getInstanceFor(Objects.requireNonNull(device));
        return requester -> levelOf(requester, roster);
    }

    AccessLevel levelOf(Jid requester, Roster roster) {
        BareJid bare = requester.asBareJid();
        if (setters.contains(bare) || inGroup(roster, bare, setterGroups)) {
            return AccessLevel.SET;
        }
        if (getters.contains(bare) || inGroup(roster, bare, getterGroups) || getterDomains.contains(bare.getDomain()
                .toString())) {
            return AccessLevel.GET;
        }
        return AccessLevel.NONE;
    }

    private static boolean inGroup(Roster roster, BareJid jid, Set<String> groups) {
        if (groups.isEmpty()) {
            return false;
        }
        RosterEntry entry = roster.getEntry(jid);
        if (entry == null) {
            return false;
        }
        for (RosterGroup g : entry.getGroups()) {
            if (groups.contains(g.getName())) {
                return true;
            }
        }
        return false;
    }
}
