package sabot.fleet;

import java.util.Collection;
import java.util.EnumMap;
import java.util.HashSet;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.stream.Collectors;
import java.util.stream.Stream;

import org.jivesoftware.smack.SmackException;
import org.jivesoftware.smack.XMPPConnection;
import org.jivesoftware.smack.roster.Roster;
import org.jivesoftware.smack.roster.RosterEntry;
import org.jivesoftware.smack.roster.RosterGroup;
import org.jivesoftware.smack.roster.RosterLoadedListener;
import org.jxmpp.jid.BareJid;
import org.jxmpp.jid.Jid;

import sabot.controlml.AccessPolicy;
import sabot.controlml.Role;

/**
 * Who has which {@link Role} on a device (docs/CONTROLML.md section 9). Roles are granted where the lab administers
 * its accounts: its XMPP server's <b>shared groups</b> (Prosody's {@code mod_groups}, ejabberd's shared roster
 * groups), which the server writes into the device's roster with the group's name, and which no other account can
 * write there. The rules name, per role, the groups whose members hold it (and, for fleet tools and tests, bare JIDs
 * and whole domains); a requester holds the highest role it is granted, and nothing when it is granted none (deny by
 * default). The roster is read at each request, so a change of the server's groups takes effect on a running device
 * as soon as the server's roster push arrives.
 */
public final class AccessRules {

    /** The shared group of the lab's robots: how a workbench tells a robot from an account that claims to be one. */
    public static final String ROBOTS_GROUP = "sabot-robots";
    /**
     * The shared group of the robots enrolled and not yet approved, asking for access ({@link Enrolment}): its
     * members see no group, so they find no role and obey nobody; every other account sees them in it.
     */
    public static final String ENROLLING_GROUP = "sabot-enrolling";
    /** The lab's shared groups of the roles, a device's defaults: the role's name, plural, after "sabot-". */
    public static final String OBSERVERS_GROUP = "sabot-observers", OPERATORS_GROUP = "sabot-operators",
            MAINTAINERS_GROUP = "sabot-maintainers";
    /** The lab's shared group of each role. */
    public static final Map<Role, String> LAB_GROUPS = Map.of(Role.OBSERVER, OBSERVERS_GROUP, Role.OPERATOR,
            OPERATORS_GROUP, Role.MAINTAINER, MAINTAINERS_GROUP);
    private static final List<Role> GRANTABLE = List.of(Role.MAINTAINER, Role.OPERATOR, Role.OBSERVER);

    private final Map<Role, Set<String>> groups;
    private final Map<Role, Set<BareJid>> jids;
    private final Map<Role, Set<String>> domains;

    private AccessRules(Map<Role, Set<String>> groups, Map<Role, Set<BareJid>> jids, Map<Role, Set<String>> domains) {
        this.groups = groups;
        this.jids = jids;
        this.domains = domains;
    }

    /** @return rules that grant nothing: every requester is refused */
    public static AccessRules none() {
        return new AccessRules(empty(), empty(), empty());
    }

    /** @return the lab's groups of {@link #LAB_GROUPS}, one per role */
    public static AccessRules labGroups() {
        AccessRules r = none();
        for (Role role : GRANTABLE) {
            r = r.withGroups(role, Set.of(LAB_GROUPS.get(role)));
        }
        return r;
    }

    /** @return these rules, and the members of {@code names} (roster group names) hold {@code role} */
    public AccessRules withGroups(Role role, Collection<String> names) {
        return new AccessRules(adding(groups, role, names), jids, domains);
    }

    /** @return these rules, and {@code jid} holds {@code role} */
    public AccessRules withJid(Role role, BareJid jid) {
        return new AccessRules(groups, adding(jids, role, Set.of(Objects.requireNonNull(jid))), domains);
    }

    /** @return these rules, and every account of {@code names} (domains) holds {@code role} */
    public AccessRules withDomains(Role role, Collection<String> names) {
        return new AccessRules(groups, jids, adding(domains, role, names));
    }

    /** @return the groups granting {@code role}; empty when none */
    public Set<String> groupsOf(Role role) {
        return groups.getOrDefault(role, Set.of());
    }

    /** @return true when no rule grants anything */
    public boolean grantsNothing() {
        return groups.values().stream().allMatch(Set::isEmpty) && jids.values().stream().allMatch(Set::isEmpty)
                && domains.values().stream().allMatch(Set::isEmpty);
    }

    /**
     * @return the policy these rules define on a device's connection (its roster supplies the groups). The device's
     *         roster is reloaded after each change the server pushes: ejabberd 23.01 pushes a shared group's change as
     *         an item carrying only that group, and a removal from one group as the item's removal, although the
     *         account may be in other groups; the reloaded roster has each item with all its groups.
     */
    public AccessPolicy on(XMPPConnection device) {
        Roster roster = Roster.getInstanceFor(Objects.requireNonNull(device));
        roster.addRosterListener(new ReloadAfterPush(roster));
        return requester -> roleOf(requester.asBareJid(), groupsIn(roster, requester));
    }

    /**
     * Reloads a roster after the server pushed a change; one reload at a time, and one more when pushes arrived
     * during it. A reload that changes nothing ends the chain (it fires no event). A chain in which the roster changed
     * is followed by one more reload {@value #SETTLE_MS} ms after its end: ejabberd 23.01 pushes an account's addition
     * to a shared group before it writes it (mod_shared_roster's {@code add_user_to_group2}; a removal it writes
     * first), so the reloads right after the push may read the roster from before the change, twice in a row on a
     * cluster, where the write and the caches' clearing go to every node; the later reload reads it written.
     */
    private static final class ReloadAfterPush extends RosterEntriesListener {
        private final Roster roster;
        private final AtomicBoolean reloading = new AtomicBoolean();
        private final AtomicBoolean again = new AtomicBoolean();
        /** The roster changed during the chain under way: its end schedules the settling reload. */
        private final AtomicBoolean settle = new AtomicBoolean();

        ReloadAfterPush(Roster roster) {
            this.roster = roster;
        }

        @Override
        protected void entriesChanged() {
            settle.set(true); // (a settling reload that changes nothing schedules none: the chain ends there)
            if (!reloading.compareAndSet(false, true)) {
                again.set(true);
                return;
            }
            reload();
        }

        /** The settling reload: its changes, if any, make a chain of their own that schedules no other. */
        private void settling() {
            if (!reloading.compareAndSet(false, true)) {
                again.set(true); // a chain under way: it reads the roster after this moment anyway
                return;
            }
            reload();
        }

        private void reload() {
            RosterLoadedListener loaded = new RosterLoadedListener() {
                @Override
                public void onRosterLoaded(Roster r) {
                    done(this);
                }

                @Override
                public void onRosterLoadingFailed(Exception exception) {
                    done(this);
                }
            };
            roster.addRosterLoadedListener(loaded); // before the reload, which may end before the next line
            try {
                roster.reload();
            } catch (SmackException.NotLoggedInException | SmackException.NotConnectedException e) {
                done(loaded); // the next login loads it whole
            } catch (InterruptedException e) {
                done(loaded);
                Thread.currentThread().interrupt();
            }
        }

        private void done(RosterLoadedListener loaded) {
            roster.removeRosterLoadedListener(loaded);
            reloading.set(false);
            if (again.getAndSet(false)) {
                if (reloading.compareAndSet(false, true)) {
                    reload();
                }
            } else if (settle.getAndSet(false)) {
                CompletableFuture.delayedExecutor(SETTLE_MS, TimeUnit.MILLISECONDS).execute(this::settling);
            }
        }
    }

    /** How long after a chain of reloads that a push started the settling reload comes ({@link ReloadAfterPush}). */
    static final long SETTLE_MS = 300;

    /**
     * @param requester    a requester's bare JID
     * @param rosterGroups the groups the device's roster puts it in
     * @return its highest role, {@link Role#NONE} when granted none
     */
    public Role roleOf(BareJid requester, Collection<String> rosterGroups) {
        for (Role role : GRANTABLE) {
            if (jids.getOrDefault(role, Set.of()).contains(requester) || domains.getOrDefault(role, Set.of())
                    .contains(requester.getDomain().toString()) || rosterGroups.stream().anyMatch(groupsOf(
                            role)::contains)) {
                return role;
            }
        }
        return Role.NONE;
    }

    /** @return the groups {@code requester} is in on {@code roster} (empty when it is not there) */
    public static Set<String> groupsIn(Roster roster, Jid requester) {
        RosterEntry entry = roster.getEntry(requester.asBareJid());
        if (entry == null) {
            return Set.of();
        }
        Set<String> names = new HashSet<>();
        for (RosterGroup g : entry.getGroups()) {
            names.add(g.getName());
        }
        return names;
    }

    /** @return one line for a log, e.g. {@code maintainer: groups [sabot-maintainers]; operator: ...} */
    public String describe() {
        if (grantsNothing()) {
            return "nobody has a role";
        }
        return GRANTABLE.stream().map(role -> role.label() + ": " + String.join(", ", Stream.of(
                part("groups", groups.get(role)), part("accounts", jids.get(role)), part("domains", domains.get(
                        role))).filter(p -> !p.isEmpty()).toList())).collect(Collectors.joining("; "));
    }

    private static String part(String what, Set<?> names) {
        return names == null || names.isEmpty() ? "" : what + " " + names.stream().map(Object::toString).sorted()
                .toList();
    }

    private static <T> Map<Role, Set<T>> empty() {
        return new EnumMap<>(Role.class);
    }

    private static <T> Map<Role, Set<T>> adding(Map<Role, Set<T>> map, Role role, Collection<T> more) {
        if (role == null || role == Role.NONE) {
            throw new IllegalArgumentException("a grant names a role: observer, operator or maintainer");
        }
        Map<Role, Set<T>> copy = new EnumMap<>(Role.class);
        copy.putAll(map);
        Set<T> set = new LinkedHashSet<>(copy.getOrDefault(role, Set.of()));
        set.addAll(more);
        copy.put(role, Set.copyOf(set));
        return copy;
    }
}
