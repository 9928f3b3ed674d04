package sabot.workbench.controlml.internal;

import java.util.Collection;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Set;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;
import java.util.function.Supplier;

import org.jivesoftware.smack.packet.Presence;
import org.jivesoftware.smack.roster.RosterEntry;
import org.jivesoftware.smack.roster.RosterGroup;
import org.jivesoftware.smackx.muc.MultiUserChatManager;
import org.jxmpp.jid.EntityBareJid;
import org.jxmpp.jid.impl.JidCreate;
import org.jxmpp.stringprep.XmppStringprepException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

import sabot.controlml.PresenceLevel;
import sabot.fleet.AccessRules;
import sabot.fleet.FleetException;
import sabot.fleet.FleetLobby;
import sabot.fleet.PresenceLevels;
import sabot.fleet.RosterCompiler;
import sabot.fleet.RosterEntriesListener;
import sabot.workbench.fleet.Availability;
import sabot.workbench.fleet.RobotState;

/**
 * Which robots the workbench follows, and whether they are there: the roster's entries in
 * {@link ControlMlFleet#ROBOTS_GROUP} (roster rule 12: the robots configured with the account are asked for), the
 * fleet lobby's robots subscribed to (rule 11), their presence levels, and a periodic reconciliation that asks again
 * for a subscription cut short and reads a presence missed. Robots coming online are followed ({@link FleetTelemetry}).
 * Runs on the connection thread; Smack's roster callbacks are queued there.
 */
final class FleetRoster {

    /** The vCard ROLE of the devices roster rule 11 follows (docs/IDENTITY.md; the onboard product publishes it). */
    static final String ROBOT_ROLE = "robot";
    /**
     * How often the robots' roster state is checked again while online: a subscription handshake cut short (the
     * workbench reconnected in between) is asked for again, and a presence missed is read from the roster.
     */
    static final long RECONCILE_MS = 2000;

    private static final Logger LOG = LoggerFactory.getLogger("sabot.workbench.controlml");

    private final RobotRegistry registry;
    private final FleetTelemetry telemetry;
    private final ScheduledExecutorService connector;
    private final Supplier<FleetSession> current;

    /**
     * @param connector the connection thread
     * @param current   the session now live, or null
     */
    FleetRoster(RobotRegistry registry, FleetTelemetry telemetry, ScheduledExecutorService connector,
            Supplier<FleetSession> current) {
        this.registry = registry;
        this.telemetry = telemetry;
        this.connector = connector;
        this.current = current;
    }

    /** Before login: the session's roster changes and presences come here. */
    void listen(FleetSession s) {
        s.roster().addRosterListener(new Listener(s));
    }

    /**
     * Connection thread, once logged in and the roster loaded: asks the configured robots not in the roster for their
     * presence, takes the roster's robots, and joins the lobby when one is configured.
     *
     * @param configured the robots of the account's settings (bare JIDs)
     * @param lobby      the fleet lobby's room, or empty for none
     */
    void start(FleetSession s, Collection<String> configured, String lobby) throws Exception {
        for (String r : configured) {
            EntityBareJid jid = JidCreate.entityBareFrom(r);
            if (s.roster().getEntry(jid) == null) {
                s.roster().createItemAndRequestSubscription(jid, jid.getLocalpart().toString(), new String[] {
                        ControlMlFleet.ROBOTS_GROUP });
            }
        }
        refresh(s);
        if (!lobby.isEmpty()) {
            joinLobby(s, lobby);
        }
    }

    /** Connection thread: from now on, every {@link #RECONCILE_MS} while the session lives. */
    void scheduleReconcile(FleetSession s) {
        connector.schedule(() -> reconcile(s), RECONCILE_MS, TimeUnit.MILLISECONDS);
    }

    /**
     * The robots: the roster's entries in {@link ControlMlFleet#ROBOTS_GROUP} (the robots this workbench follows) and
     * in the server's shared group of the lab's robots ({@link AccessRules#ROBOTS_GROUP}, which the server writes);
     * and the robots asking for access, in its quarantine group ({@link AccessRules#ENROLLING_GROUP}).
     */
    private void refresh(FleetSession s) {
        Set<String> now = new LinkedHashSet<>();
        for (String groupName : List.of(ControlMlFleet.ROBOTS_GROUP, AccessRules.ROBOTS_GROUP)) {
            RosterGroup group = s.roster().getGroup(groupName);
            if (group == null) {
                continue;
            }
            for (RosterEntry e : group.getEntries()) {
                String jid = e.getJid().toString();
                if (!now.add(jid)) {
                    continue; // in both groups
                }
                String name = e.getName() != null && !e.getName().isBlank() ? e.getName() : e.getJid().getLocalpartOrNull()
                        == null ? jid : e.getJid().getLocalpartOrNull().toString();
                RobotState known = registry.robot(jid);
                if (known == null) {
                    registry.add(jid, name);
                } else if (!known.name().equals(name)) {
                    registry.update(jid, r -> r.withName(name));
                }
                presence(s, s.roster().getPresence(e.getJid()));
            }
        }
        for (String jid : registry.jids()) {
            if (!now.contains(jid)) {
                registry.remove(jid);
            }
        }
        // the robots asking for access: in the server's quarantine group, not (yet) one of the fleet's
        RosterGroup asking = s.roster().getGroup(AccessRules.ENROLLING_GROUP);
        registry.setAccessRequests(asking == null ? List.of() : asking.getEntries().stream().map(e -> e.getJid()
                .toString()).filter(j -> !now.contains(j)).toList());
    }

    /**
     * Connection thread: roster rule 11. Joins the fleet lobby (a XEP-0045 room every online device joins) and
     * subscribes to the occupants that the server says are robots (its robots' group) and whose vCard says so too
     * ({@link #ROBOT_ROLE}), now and whenever an occupant comes in; an occupant that only says it is a robot is logged
     * and not followed. A lobby that cannot be joined leaves the workbench with its roster (rule 12); the reason is logged.
     */
    private void joinLobby(FleetSession s, String room) {
        try {
            EntityBareJid jid = JidCreate.entityBareFrom(room);
            FleetLobby lobby = new FleetLobby(s.connection(), jid);
            lobby.join();
            MultiUserChatManager.getInstanceFor(s.connection()).getMultiUserChat(jid).addParticipantListener(p -> {
                if (p.isAvailable()) {
                    connector.execute(() -> compile(s, lobby));
                }
            });
            LOG.info("joined the fleet lobby {}", room);
            compile(s, lobby);
        } catch (FleetException | XmppStringprepException e) {
            LOG.warn("fleet lobby {}: {}", room, e.getMessage());
        }
    }

    /** Connection thread: subscribes to the lobby's robots not yet in the roster (they then join the fleet). */
    private void compile(FleetSession s, FleetLobby lobby) {
        if (current.get() != s) {
            return;
        }
        try {
            // a robot is one the server says is: in its robots' group (those are in the roster already, and in the
            // fleet); an occupant whose own vCard says "robot" is not followed on that word
            RosterCompiler.Report report = new RosterCompiler(s.connection(), lobby, new RosterCompiler.Rules(
                    p -> ROBOT_ROLE.equals(p.role()), jid -> AccessRules.groupsIn(s.roster(), jid).contains(
                            AccessRules.ROBOTS_GROUP), Set.of(), ControlMlFleet.ROBOTS_GROUP)).compile();
            if (!report.subscribed().isEmpty()) {
                LOG.info("fleet lobby: subscribed to {}", report.subscribed());
            }
            report.rejected().forEach((jid, why) -> LOG.info("fleet lobby: {} not followed: {}", jid, why));
        } catch (FleetException e) {
            LOG.warn("fleet lobby: {}", e.getMessage());
        }
    }

    /** Connection thread, every {@link #RECONCILE_MS} while the session lives: see there. */
    private void reconcile(FleetSession s) {
        if (current.get() != s || !s.connection().isAuthenticated()) {
            return; // a lost session's roster still holds the presences it had: they would undo the loss
        }
        for (RobotState r : registry.robots()) {
            try {
                EntityBareJid jid = JidCreate.entityBareFrom(r.jid());
                RosterEntry e = s.roster().getEntry(jid);
                if (e != null && !e.canSeeHisPresence() && !e.isSubscriptionPending()) {
                    LOG.info("asking {} again for its presence (subscription {})", jid, e.getType());
                    s.roster().sendSubscriptionRequest(jid);
                }
                presence(s, s.roster().getPresence(jid));
            } catch (Exception e) {
                LOG.debug("reconciling {}: {}", r.jid(), e.toString());
            }
        }
        scheduleReconcile(s);
    }

    private void presence(FleetSession s, Presence p) {
        String jid = p.getFrom().asBareJid().toString();
        RobotState before = registry.robot(jid);
        if (before == null) {
            return;
        }
        PresenceLevel level = PresenceLevels.of(p);
        Availability a = level == null ? Availability.OFFLINE : switch (level) {
            case FREE -> Availability.FREE;
            case BUSY -> Availability.BUSY;
            case AWAY -> Availability.AWAY;
        };
        String reason = p.getStatus() == null ? "" : p.getStatus();
        if (before.availability() == a && before.reason().equals(reason)) {
            return;
        }
        registry.update(jid, r -> r.withPresence(a, reason));
        if (before.availability() == Availability.OFFLINE && a != Availability.OFFLINE && current.get() == s) {
            telemetry.online(s, jid);
            connector.execute(() -> telemetry.follow(s, jid, 0));
        }
    }

    private final class Listener extends RosterEntriesListener {
        private final FleetSession s;

        Listener(FleetSession s) {
            this.s = s;
        }

        @Override
        protected void entriesChanged() {
            connector.execute(() -> {
                if (current.get() == s) {
                    refresh(s);
                }
            });
        }

        @Override
        public void presenceChanged(Presence presence) {
            FleetSession now = current.get();
            if (now == s || now == null) {
                presence(s, presence);
            }
        }
    }
}
